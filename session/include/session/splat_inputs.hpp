// Files shown as QNV splats: .qnv streams, and meshes and volumes encoded on the fly
// (paper sections 2.1 and 3.2), each opened as a world holding one QuantizedNormalVectors
// node (docs/vrml-extensions.md).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <utility>

#include "base/fetch.hpp"
#include "render/splat_source.hpp"
#include "splats/lod_tree.hpp"
#include "splats/readers.hpp"

namespace gs::session {

/// True for local inputs that are not VRML97 worlds and have no Viewpoint of their own:
/// QNV streams, meshes, volumes and Gaussian splatting scenes, as formats::classifyFile
/// decides (content first, then name), and a glTF asset of Gaussian splats alone
/// (splats::gltfDrawsOnlyGaussians; any other glTF opens as a world of its own).
bool isSplatInput(const std::string& path);

/// The index URL when `input` names a QNV tileset (docs/tilesets.md), else "": an index
/// file (local: its signature, else its name; URL: the name ".qnvt"), a local folder
/// holding index.qnvt, or an http(s) URL ending in '/' (its "index.qnvt").
std::string tilesetIndexOf(const std::string& input);

/// The VRML97 world an input that is not a VRML97 file opens as: a mesh becomes one
/// Shape with an IndexedFaceSet (drawn as polygons, or as splats with --mode splats);
/// a .qnv stream or a volume becomes one QuantizedNormalVectors node naming the file.
/// Throws qnv::InputError when a mesh cannot be read.
std::string worldTextFor(const std::string& path);

/// True when the local file `path` is a 3D Gaussian splatting scene (docs/splats.md): what
/// formats::classifyFile calls gaussianSplats, a glTF using KHR_gaussian_splatting, or a
/// QNV Gaussian stream (isGaussianQnvFile).
bool isGaussianSplatFile(const std::string& path);
/// True when the local file `path` is a QNV stream of Gaussians (kind 3, byte 10 of its
/// header; splats/qnv_gaussians.hpp). False when it cannot be read.
bool isGaussianQnvFile(const std::string& path);

/// True when the local file `path` is the index of a tileset of Gaussians (its template's
/// kind, byte 26, is qnv::StreamKind::gaussian; splats/gaussian_tileset.hpp). False when
/// it cannot be read.
bool isGaussianTilesetIndex(const std::string& path);

/// The VRML97 text of the world a Gaussian splatting scene opens as: its node under a
/// Transform turning it 180 degrees about Z (captures are y-down; docs/splats.md "Axes"),
/// or, `turned` false (a LAS point cloud, z up), not turned.
std::string gaussianWorldText(const std::string& path, bool turned = true);

/// Side files of the scene at `sceneUrl` (SOG images, glTF buffers) through `fetcher`
/// (which must outlive the reader), named by the scene, so the rules of what content may
/// reference apply (base::mayReference); names with "..", a scheme or a leading '/' are
/// refused; a name is percent-encoded in a URL (sideFileUrl).
splats::SideFileReader sideFileReader(base::Fetcher& fetcher, const std::string& sceneUrl);

/// The URL of the side file `relative` (a file's own name: a glTF's uri percent-decoded,
/// an SOG's as meta.json writes it) of the scene
/// at `sceneUrl`, resolved against it (percent-encoded where `sceneUrl` is a URL, as is
/// where it is a local path); empty with `why` set for a name with "..", a scheme or a
/// leading '/' (sideFileReader's rule).
std::string sideFileUrl(const std::string& sceneUrl, const std::string& relative, std::string& why);

/// A Gaussian splatting scene held in `bytes` (named `name`: a path or URL), read by
/// splats::readGaussians and sorted by importance. Null with `error` naming the input and
/// the reason when it cannot be read.
std::shared_ptr<const render::SplatSet> gaussianSet(const std::string& bytes,
                                                    const std::string& name,
                                                    const splats::SideFileReader& sideFiles,
                                                    std::string& error);

/// A local Gaussian splatting scene read whole (splats::readGaussians; side files from
/// its folder or below only) and sorted by importance. Null with `error` naming the file
/// and the reason when it cannot be read.
std::shared_ptr<const render::SplatSet> loadGaussianFile(const std::string& path,
                                                         std::string& error);

/// The level-of-detail tree of `cloud` (splats::buildLodTree, default options), for a thread
/// of its own: a progressive stream's prefix or a Gaussian tileset's chosen splats. When it
/// cannot be built (too many splats, no memory): no tree and why, naming `url` ("URL: no
/// level-of-detail tree for its N splats (reason)"; the caller says what is drawn instead).
/// Neither when `cancel` became true (a session closing, a set replaced). Never throws.
std::pair<std::shared_ptr<const splats::LodTree>, std::string> buildTreeOf(
    std::shared_ptr<const splats::GaussianCloud> cloud, std::shared_ptr<std::atomic<bool>> cancel,
    const std::string& url);

/// The VRML97 text of a world holding one QuantizedNormalVectors node whose url is
/// `path` (a world named after the file itself uses its file name, which resolves to it) (quotes
/// and backslashes escaped), with EXAMINE navigation.
std::string splatWorldText(const std::string& path);

/// The application's SplatLoader: a local .qnv file decoded whole, or a mesh or volume
/// file encoded with every vector kept (the level of detail then picks the prefix).
/// Only local files (paths and file:// URLs); errors name the file and the reason.
render::SplatLoader splatLoader();

}  // namespace gs::session
