// The one exception type of the qnv module: malformed input (a mesh or volume file, a
// .qnv stream header) and impossible encoder parameters.
#pragma once

#include <stdexcept>
#include <string>

namespace gs::qnv {

/// Thrown by readers and encoders. what() is a whole sentence a user can act on and
/// names the input: "bunny.ply:12: expected 3 vertex indices, got 2",
/// "CThead.nhdr: unsupported NRRD type 'block'".
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace gs::qnv
