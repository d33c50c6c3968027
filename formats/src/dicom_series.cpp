// DICOM series from a folder or a DICOMDIR (formats/dicom_reader.hpp): find the image
// files, read each (dicom_reader.cpp), keep the largest series, sort its slices along
// their normal and stack them.
#include <gdcmDataSet.h>
#include <gdcmItem.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <glm/geometric.hpp>

#include "base/file.hpp"
#include "base/text.hpp"
#include "dicom_internal.hpp"

namespace gs::formats {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kDicomMaxFiles = 100000;
// One file: the largest volume's samples at 8 bytes, plus headers.
constexpr std::size_t kDicomMaxFileBytes = kMaxVoxels * 8 + (std::size_t{64} << 20);

std::string dicomReadWhole(const std::string& path) {
  std::string bytes, error;
  if (!base::readFile(path, bytes, error, kDicomMaxFileBytes)) throw InputError(error);
  return bytes;
}

bool dicomNameIsDicomdir(const fs::path& p) {
  std::string n = p.filename().string();
  for (char& c : n) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return n == "DICOMDIR";
}

bool dicomFileHasMagic(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  char head[132] = {};
  return in.read(head, sizeof head) && hasDicomMagic(std::string_view(head, sizeof head));
}

// The image files a DICOMDIR lists (PS3.3 F.3: Directory Record Sequence (0004,1220),
// records of type IMAGE, Referenced File ID (0004,1500)), inside its folder only.
std::vector<fs::path> dicomdirFiles(const std::string& path) {
  const std::string bytes = dicomReadWhole(path);
  detail::scanDicomFile(bytes, path);  // bounds every length before GDCM reads
  std::istringstream in(bytes);
  gdcm::Reader reader;
  reader.SetStream(in);
  bool read = false;
  try {
    read = reader.Read();
  } catch (...) {
    read = false;
  }
  if (!read) throw InputError(path + ": a DICOMDIR GDCM cannot read");
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  const gdcm::Tag records(0x0004, 0x1220);
  if (!ds.FindDataElement(records))
    throw InputError(path + ": a DICOMDIR without a Directory Record Sequence (0004,1220)");
  const gdcm::SmartPointer<gdcm::SequenceOfItems> sq = ds.GetDataElement(records).GetValueAsSQ();
  std::vector<fs::path> files;
  const fs::path dir = fs::path(path).parent_path();
  const auto text = [](const gdcm::DataSet& item, std::uint16_t e) {
    const gdcm::Tag tag(0x0004, e);
    if (!item.FindDataElement(tag)) return std::string();
    const gdcm::ByteValue* bv = item.GetDataElement(tag).GetByteValue();
    if (!bv || !bv->GetPointer()) return std::string();
    std::string s(bv->GetPointer(), std::min<std::size_t>(bv->GetLength(), 1024));
    while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
    return s;
  };
  for (gdcm::SequenceOfItems::SizeType i = 1; sq && i <= sq->GetNumberOfItems(); ++i) {
    const gdcm::DataSet& item = sq->GetItem(i).GetNestedDataSet();
    if (text(item, 0x1430) != "IMAGE") continue;
    const std::string id = text(item, 0x1500);
    if (id.empty()) continue;
    fs::path rel;
    std::size_t at = 0;
    while (at <= id.size()) {
      const std::size_t end = std::min(id.find('\\', at), id.size());
      const std::string part = id.substr(at, end - at);
      if (part.empty() || part == "." || part == ".." || part.find('/') != std::string::npos)
        throw InputError(path + ": Referenced File ID '" + id +
                         "' leaves the DICOMDIR's folder; only files below it are read");
      rel /= part;
      at = end + 1;
    }
    files.push_back(dir / rel);
    if (files.size() > kDicomMaxFiles)
      throw InputError(path + ": more than " + std::to_string(kDicomMaxFiles) + " images");
  }
  if (files.empty()) throw InputError(path + ": the DICOMDIR lists no images");
  return files;
}

std::vector<fs::path> dicomFolderFiles(const std::string& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec),
      end;
  if (ec) throw InputError("cannot open " + folder + ": " + ec.message());
  std::size_t seen = 0;
  for (; it != end; it.increment(ec)) {
    if (ec) throw InputError("cannot list " + folder + ": " + ec.message());
    if (++seen > kDicomMaxFiles)
      throw InputError(folder + ": more than " + std::to_string(kDicomMaxFiles) +
                       " files; open a series' folder");
    if (!it->is_regular_file(ec) || dicomNameIsDicomdir(it->path())) continue;
    if (dicomFileHasMagic(it->path())) files.push_back(it->path());
  }
  if (files.empty())
    throw InputError(folder + ": no DICOM images in the folder (no file with 'DICM' at byte 128)");
  std::sort(files.begin(), files.end());
  return files;
}

std::string dicomShortName(const fs::path& p) {
  return p.filename().string();
}

// Stacks the slices of one series (see dicom_reader.hpp for the order).
DicomVolume stackDicomSeries(const std::string& path, std::vector<detail::DicomSlice> slices,
                             const std::vector<std::string>& names,
                             std::vector<std::string> notes) {
  if (slices.size() == 1) {
    DicomVolume v = std::move(slices.front().image);
    v.notes = std::move(notes);
    return v;
  }
  const detail::DicomSlice& first = slices.front();
  const glm::uvec3 d0 = first.image.volume.dims;
  for (std::size_t i = 1; i < slices.size(); ++i) {
    const glm::uvec3 d = slices[i].image.volume.dims;
    if (d.x != d0.x || d.y != d0.y)
      throw InputError(path + ": series has slices of different sizes: " + names.front() + " " +
                       std::to_string(d0.x) + "x" + std::to_string(d0.y) + ", " + names[i] + " " +
                       std::to_string(d.x) + "x" + std::to_string(d.y));
    if (d.z != 1 || d0.z != 1)
      throw InputError(path + ": series mixes a multi-frame file with others (" +
                       (d.z != 1 ? names[i] : names.front()) + "); open the file alone");
  }
  const glm::dvec3 n = glm::normalize(glm::cross(first.row, first.column));
  bool positions = true;
  for (std::size_t i = 0; i < slices.size(); ++i) {
    positions = positions && slices[i].hasPosition;
    const glm::dvec3 ni = glm::cross(slices[i].row, slices[i].column);
    if (glm::dot(ni, n) < 0.999)
      throw InputError(path + ": series mixes orientations: " + names.front() + " and " + names[i] +
                       " have different Image Orientation (Patient)");
  }
  std::vector<std::size_t> order(slices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<double> key(slices.size());
  for (std::size_t i = 0; i < slices.size(); ++i)
    key[i] = positions ? -glm::dot(slices[i].position, n) : double(slices[i].instance);
  std::stable_sort(order.begin(), order.end(),
                   [&key](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  double step = 0.0;
  if (positions) {
    double lo = 1e300, hi = 0.0, sum = 0.0;
    for (std::size_t k = 1; k < order.size(); ++k) {
      const double s = key[order[k]] - key[order[k - 1]];
      if (s < 1e-4)
        throw InputError(path + ": two slices at the same position: " + names[order[k - 1]] + ", " +
                         names[order[k]] + " (" + std::to_string(-key[order[k]]) +
                         " mm along the normal)");
      lo = std::min(lo, s), hi = std::max(hi, s), sum += s;
    }
    step = sum / static_cast<double>(order.size() - 1);
    if (hi - lo > 0.01 * step + 1e-3)
      notes.push_back("slice steps vary from " + std::to_string(lo) + " to " + std::to_string(hi) +
                      " mm; their mean, " + std::to_string(step) + " mm, is the spacing");
  } else {
    step = first.between > 0.0 ? first.between : first.thickness > 0.0 ? first.thickness : 1.0;
    notes.push_back("slices without Image Position (Patient): stacked by Instance Number, " +
                    std::to_string(step) +
                    " mm apart (Spacing Between Slices, else Slice "
                    "Thickness)");
  }

  DicomVolume v = std::move(slices[order.front()].image);
  v.notes = std::move(notes);
  v.files = slices.size();
  Volume& vol = v.volume;
  const std::size_t sliceVoxels = std::size_t{d0.x} * d0.y;
  if (sliceVoxels * slices.size() > kMaxVoxels)
    throw InputError(path + ": " + std::to_string(sliceVoxels * slices.size()) +
                     " voxels exceed the limit of " + std::to_string(kMaxVoxels));
  vol.dims.z = static_cast<std::uint32_t>(slices.size());
  vol.spacing.z = static_cast<float>(step);
  vol.samples.resize(sliceVoxels * slices.size());
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::vector<float>& src = slices[order[k]].image.volume.samples;
    std::copy(src.begin(), src.end(),
              vol.samples.begin() + static_cast<std::ptrdiff_t>(k * sliceVoxels));
  }
  return v;
}

}  // namespace

DicomVolume detail::loadDicomHere(const std::string& path) {
  std::error_code ec;
  std::vector<fs::path> files;
  const std::string where = path;
  if (fs::is_directory(path, ec)) {
    const fs::path dicomdir = fs::path(path) / "DICOMDIR";
    files = fs::is_regular_file(dicomdir, ec) ? dicomdirFiles(dicomdir.string())
                                              : dicomFolderFiles(path);
  } else {
    const std::string bytes = dicomReadWhole(path);
    const detail::DicomMeta meta = detail::scanDicomFile(bytes, path);
    if (meta.sopClass != detail::kDicomdirSopClass) return readDicomHere(bytes, path);
    files = dicomdirFiles(path);
  }

  // Read every file; group by series.
  std::vector<detail::DicomSlice> slices;
  std::vector<std::string> names;
  std::map<std::string, std::vector<std::size_t>> series;
  std::size_t voxels = 0;
  for (const fs::path& f : files) {
    const std::string name = f.string();
    detail::DicomSlice s = detail::readDicomSlice(dicomReadWhole(name), name);
    voxels += s.image.volume.samples.size();
    if (voxels > kMaxVoxels)
      throw InputError(path + ": the images hold more than " + std::to_string(kMaxVoxels) +
                       " voxels");
    series[s.seriesUid].push_back(slices.size());
    slices.push_back(std::move(s));
    names.push_back(dicomShortName(f));
  }
  // The largest series first; one that does not stack (sizes, orientations, positions)
  // gives way to the next, with a note; when none stacks, the largest one's error.
  std::vector<const std::pair<const std::string, std::vector<std::size_t>>*> bySize;
  for (const auto& entry : series) bySize.push_back(&entry);
  std::stable_sort(bySize.begin(), bySize.end(), [](const auto* a, const auto* b) {
    return a->second.size() > b->second.size();
  });
  std::vector<std::string> skipped;
  std::optional<InputError> firstError;
  for (const auto* chosen : bySize) {
    std::vector<std::string> notes;
    if (series.size() > 1)
      notes.push_back(std::to_string(series.size()) + " series in " + where + "; read series " +
                      (chosen->first.empty() ? "(no UID)" : chosen->first) + " (" +
                      std::to_string(chosen->second.size()) + " of " +
                      std::to_string(slices.size()) + " images), the largest that stacks; " +
                      "open another's files alone to read it");
    for (const std::string& why : skipped) notes.push_back("skipped: " + why);
    std::vector<detail::DicomSlice> kept;
    std::vector<std::string> keptNames;
    for (std::size_t i : chosen->second) {
      kept.push_back(series.size() == 1 ? std::move(slices[i]) : slices[i]);
      keptNames.push_back(names[i]);
    }
    try {
      return stackDicomSeries(path, std::move(kept), keptNames, std::move(notes));
    } catch (const InputError& e) {
      if (!firstError) firstError = e;
      skipped.push_back(e.what());
      if (skipped.size() > 8) break;
    }
  }
  throw *firstError;
}

bool isDicomPath(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return dicomFileHasMagic(path);
  if (fs::is_regular_file(fs::path(path) / "DICOMDIR", ec)) return true;
  std::size_t looked = 0;
  for (fs::directory_iterator it(path, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end && looked < 64; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    ++looked;
    if (dicomFileHasMagic(it->path())) return true;
  }
  return false;
}

}  // namespace gs::formats
