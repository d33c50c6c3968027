// readDicom and loadDicom in a child process (base/isolated_process.hpp): GDCM allocates
// lengths read from a file before it reads them (an encapsulated Pixel Data fragment of a
// small mutated file asked for 4.28 GB), which no check outside GDCM can bound. The child
// reads as dicom_reader.cpp and dicom_series.cpp do and sends the DicomVolume back: its
// description in one frame, its samples in frames of up to 64 MiB.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "base/isolated_process.hpp"
#include "dicom_internal.hpp"
#include "formats/dicom_reader.hpp"
#include "qnv/error.hpp"

namespace gs::formats {

namespace {

constexpr std::size_t kSampleFrameFloats = std::size_t{16} << 20;  // 64 MiB

// Values in a frame: numbers as their bytes (both ends are the same program), strings
// and lists with their length first.
class Writer {
 public:
  template <typename T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    bytes_ += s;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
  }
  void get(std::string& s) {
    std::uint64_t n = 0;
    get(n);
    need(n);
    s.assign(bytes_.substr(at_, static_cast<std::size_t>(n)));
    at_ += static_cast<std::size_t>(n);
  }

 private:
  void need(std::uint64_t n) {
    if (n > bytes_.size() - at_)
      throw base::IsolationError("the DICOM reader sent a short description");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

void send(const DicomVolume& d, base::FrameWriter& out) {
  Writer w;
  const qnv::Volume& v = d.volume;
  w.put(v.dims);
  w.put(v.spacing);
  w.put(v.origin);
  w.put(v.sourceType);
  w.put(static_cast<std::uint64_t>(v.samples.size()));
  w.put(d.modality);
  w.put(d.rescaleType);
  w.put(d.slope);
  w.put(d.intercept);
  w.put(static_cast<std::uint64_t>(d.windows.size()));
  for (const DicomWindow& win : d.windows) {
    w.put(win.center);
    w.put(win.width);
    w.put(win.explanation);
  }
  w.put(d.rowDirection);
  w.put(d.columnDirection);
  w.put(d.sliceDirection);
  w.put(d.transferSyntax);
  w.put(static_cast<std::uint64_t>(d.files));
  w.put(static_cast<std::uint64_t>(d.notes.size()));
  for (const std::string& note : d.notes) w.put(note);
  out.write(w.bytes());
  for (std::size_t i = 0; i < v.samples.size(); i += kSampleFrameFloats) {
    const std::size_t n = std::min(kSampleFrameFloats, v.samples.size() - i);
    out.write(
        std::string_view(reinterpret_cast<const char*>(v.samples.data() + i), n * sizeof(float)));
  }
}

// A list length that the rest of the description could hold (each entry takes at least
// 8 bytes), so that a bad frame cannot ask for a huge list.
std::size_t listLength(Reader& r, std::size_t frameBytes) {
  std::uint64_t n = 0;
  r.get(n);
  if (n > frameBytes / 8) throw base::IsolationError("the DICOM reader sent a bad description");
  return static_cast<std::size_t>(n);
}

DicomVolume receive(base::IsolatedProcess& child) {
  const std::string head = child.next(std::uint64_t{1} << 20);
  Reader r(head);
  DicomVolume d;
  qnv::Volume& v = d.volume;
  r.get(v.dims);
  r.get(v.spacing);
  r.get(v.origin);
  r.get(v.sourceType);
  std::uint64_t samples = 0;
  r.get(samples);
  if (samples != std::uint64_t{v.dims.x} * v.dims.y * v.dims.z || samples > qnv::kMaxVoxels)
    throw base::IsolationError("the DICOM reader sent a bad volume size");
  r.get(d.modality);
  r.get(d.rescaleType);
  r.get(d.slope);
  r.get(d.intercept);
  d.windows.resize(listLength(r, head.size()));
  for (DicomWindow& win : d.windows) {
    r.get(win.center);
    r.get(win.width);
    r.get(win.explanation);
  }
  r.get(d.rowDirection);
  r.get(d.columnDirection);
  r.get(d.sliceDirection);
  r.get(d.transferSyntax);
  std::uint64_t files = 0;
  r.get(files);
  d.files = static_cast<std::size_t>(files);
  d.notes.resize(listLength(r, head.size()));
  for (std::string& note : d.notes) r.get(note);
  v.samples.resize(static_cast<std::size_t>(samples));
  for (std::size_t i = 0; i < v.samples.size(); i += kSampleFrameFloats) {
    const std::size_t n = std::min(kSampleFrameFloats, v.samples.size() - i);
    const std::string part = child.next(n * sizeof(float));
    if (part.size() != n * sizeof(float))
      throw base::IsolationError("the DICOM reader sent a short run of samples");
    std::memcpy(v.samples.data() + i, part.data(), part.size());
  }
  return d;
}

// Runs `read` in a child with memory for `inputBytes` of DICOM; errors name `name` as the
// reader's own do (the child's InputError text is the message as it is).
template <typename Read>
DicomVolume isolated(Read read, std::uint64_t inputBytes, const std::string& name) {
  base::IsolationLimits limits;
  // The decoded volume may be up to 4 bytes per voxel of kMaxVoxels beyond the files.
  limits.memoryBytes = base::isolationMemoryFor(inputBytes);
  try {
    base::IsolatedProcess child([&](base::FrameWriter& out) { send(read(), out); }, limits);
    return receive(child);
  } catch (const base::IsolationError& e) {
    const std::string what = e.what();
    // The child's own errors already name the file.
    if (what.rfind("the reader ", 0) == 0 || what.rfind("the DICOM reader ", 0) == 0 ||
        what.rfind("ran out of", 0) == 0)
      throw qnv::InputError(name + ": GDCM: " + what);
    throw qnv::InputError(what);
  }
}

std::uint64_t bytesUnder(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) {
    const auto size = std::filesystem::file_size(path, ec);
    return ec ? 0 : size;
  }
  std::uint64_t total = 0;
  std::size_t seen = 0;
  for (std::filesystem::recursive_directory_iterator it(path, ec), end;
       !ec && it != end && seen < 100000; it.increment(ec), ++seen) {
    std::error_code sizeError;
    if (it->is_regular_file(sizeError)) {
      const auto size = it->file_size(sizeError);
      if (!sizeError) total += size;
    }
  }
  return total;
}

}  // namespace

DicomVolume readDicom(std::string_view bytes, const std::string& name) {
  // The element walk here too, where a fuzzer sees it (the child walks again before GDCM).
  (void)detail::scanDicomFile(bytes, name);
  return isolated([&] { return detail::readDicomHere(bytes, name); }, bytes.size(), name);
}

DicomVolume loadDicom(const std::string& path) {
  return isolated([&] { return detail::loadDicomHere(path); }, bytesUnder(path), path);
}

}  // namespace gs::formats
