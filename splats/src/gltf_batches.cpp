// A glTF KHR_gaussian_splatting scene read a batch of splats at a time (readers.hpp:
// openGaussianBatches; docs/out-of-core.md, "Gaussian splatting scenes"): the JSON is
// read and parsed alone (tinygltf, with its file buffers emptied), and each batch's
// elements of each accessor are read by offset from the GLB's BIN chunk or from the
// .gltf's buffer files beside it. Every splat is the whole reader's (gltf_gaussians.cpp):
// the same attributes, world transforms and placement.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/byte_order.hpp"
#include "base/url.hpp"
#include "gltf/accessors.hpp"
#include "gltf_gaussians.hpp"
#include "reader_support.hpp"

namespace gs::splats {

namespace {

using detail::fail;

constexpr std::uint64_t kMaxJsonBytes = std::uint64_t{64} << 20;
/// Splat primitive instances read piecewise: each holds its accessors and placement
/// (about 2 KB); more are read whole.
constexpr std::size_t kMaxInstances = 65536;
// tinygltf 2.7 refuses an empty data: URI: four zero bytes stand for a file buffer.
constexpr const char* kPlaceholderBuffer = "data:application/octet-stream;base64,AAAAAA==";

/// Where one buffer's bytes are: a file (the GLB itself, or a buffer file beside a
/// .gltf) from `offset`, or memory (a data: URI, decoded by tinygltf), or, for a remote
/// .gltf, a buffer file fetched by its columns (`uri`, relative and percent-decoded).
struct BufferSource {
  std::uint64_t byteLength = 0;
  std::shared_ptr<detail::PieceFile> file;
  std::uint64_t offset = 0;
  const std::vector<unsigned char>* memory = nullptr;
  std::string uri;
};

/// One accessor read by offset: element i of component k at byte offset + i * stride +
/// k * component size of its buffer.
struct PieceAccessor {
  int buffer = -1;
  std::uint64_t offset = 0;
  std::size_t stride = 0, elementBytes = 0;
  int componentType = 0, components = 0;
  bool normalized = false;
  std::uint64_t count = 0;
};

/// One primitive's splats: its accessors, placement and place in the scene.
struct SplatPrimitive {
  detail::GltfSplatAttributes attributes;
  std::shared_ptr<const detail::GltfPlacement> placement;
  PieceAccessor position, rotation, scale, opacity, color;  // color: the DC, or COLOR_0
  std::vector<PieceAccessor> rest;
  std::uint64_t first = 0, count = 0;
};

/// Thrown while a remote GLB's head is read when the bytes needed have not arrived.
struct NeedMoreBytes {};

/// A glTF scene read a batch at a time from a file (GaussianBatchReader), or, from a remote
/// GLB's head, by columns (GaussianColumnDecoder: one column per accessor of its one splat
/// primitive, the elements of each read as they arrive).
class GltfGaussianBatches final : public GaussianBatchReader, public GaussianColumnDecoder {
 public:
  explicit GltfGaussianBatches(const std::string& path)
      : path_(path), file_(std::make_shared<detail::PieceFile>(path)), fileBytes_(file_->size()) {
    openBytes([this](std::uint64_t at, char* dst, std::size_t n) { file_->read(at, dst, n); });
  }
  /// A remote GLB or .gltf of `fileBytes` bytes from its first bytes `head`: NeedMoreBytes
  /// until they hold its header and JSON chunk (a .gltf: the whole file, at most 1 MiB);
  /// NotPiecewiseError for what is not read by columns.
  GltfGaussianBatches(const std::string& name, std::string_view head, std::uint64_t fileBytes)
      : path_(name), fileBytes_(fileBytes), remote_(true) {
    if (!head.starts_with("glTF")) {
      if (fileBytes > kMaxColumnsJsonBytes)
        throw NotPiecewiseError(name + ": a .gltf past 1 MiB is not read by columns");
      if (head.size() < fileBytes) throw NeedMoreBytes{};
      head = head.substr(0, static_cast<std::size_t>(fileBytes));
    }
    openBytes([head](std::uint64_t at, char* dst, std::size_t n) {
      if (at > head.size() || n > head.size() - at) throw NeedMoreBytes{};
      std::copy_n(head.data() + at, n, dst);
    });
    planColumns();
  }
  std::uint64_t size() const override { return total_; }
  int shDegree() const override { return degree_; }
  std::size_t rowBytes() const override {
    return static_cast<std::size_t>(60 + 12 * (shCoefficients(degree_) - 1));
  }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, total_ - next_));
    batch = GaussianCloud{};
    detail::allocate(batch, n, degree_);
    batch.colorSpace = colorSpace_;
    batch.kernel = Kernel::ellipse;
    for (const SplatPrimitive& p : primitives_) {
      const std::uint64_t from = std::max(next_, p.first),
                          to = std::min(next_ + n, p.first + p.count);
      if (from >= to) continue;
      place(p, from - p.first, static_cast<std::size_t>(to - from), batch,
            static_cast<std::size_t>(from - next_), nullptr);
    }
    next_ += n;
    return n;
  }
  void rewind() override { next_ = 0; }
  const std::vector<Column>& columns() const override { return columns_; }
  void decode(const std::vector<const char*>& records, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, total_);
    if (records.size() != columns_.size())
      fail(path_, "expected " + std::to_string(columns_.size()) + " columns, got " +
                      std::to_string(records.size()));
    batch = GaussianCloud{};
    detail::allocate(batch, n, degree_);
    batch.colorSpace = colorSpace_;
    batch.kernel = Kernel::ellipse;
    place(primitives_.front(), first, n, batch, 0, &records);
  }

 private:
  using ReadAt = std::function<void(std::uint64_t, char*, std::size_t)>;
  /// The GLB's or .gltf's JSON read through `readAt` (bytes at an offset of the file),
  /// then open().
  void openBytes(const ReadAt& readAt) {
    const std::string& path = path_;
    std::string json;
    std::uint64_t binOffset = 0, binBytes = 0;
    std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(20, fileBytes_)), '\0');
    readAt(0, head.data(), head.size());
    const bool glb = head.size() >= 4 && head.starts_with("glTF");
    if (glb) {
      if (head.size() < 20)
        fail(path, "GLB header needs 20 bytes, got " + std::to_string(head.size()));
      if (base::loadLe<std::uint32_t>(head.data() + 4) != 2)
        fail(path, "expected GLB version 2, got " +
                       std::to_string(base::loadLe<std::uint32_t>(head.data() + 4)));
      if (base::loadLe<std::uint32_t>(head.data() + 8) != fileBytes_)
        fail(path, "GLB length " + std::to_string(base::loadLe<std::uint32_t>(head.data() + 8)) +
                       " does not match the " + std::to_string(fileBytes_) + " bytes present");
      const std::uint64_t jsonBytes = base::loadLe<std::uint32_t>(head.data() + 12);
      if (base::loadLe<std::uint32_t>(head.data() + 16) != 0x4E4F534Au)
        fail(path, "GLB lacks a JSON chunk");
      if (jsonBytes > kMaxJsonBytes || 20 + jsonBytes > fileBytes_)
        fail(path, "GLB JSON chunk of " + std::to_string(jsonBytes) + " bytes does not fit");
      // A remote head: a JSON chunk past 1 MiB is read with the whole file instead.
      if (remote_ && jsonBytes > kMaxColumnsJsonBytes)
        throw NotPiecewiseError(path + ": a GLB JSON chunk past 1 MiB is not read by columns");
      json.resize(static_cast<std::size_t>(jsonBytes));
      readAt(20, json.data(), json.size());
      const std::uint64_t at = 20 + jsonBytes;
      if (fileBytes_ > at && fileBytes_ < at + 8) fail(path, "GLB chunk header truncated");
      if (fileBytes_ >= at + 8) {
        char chunk[8];
        readAt(at, chunk, 8);
        binBytes = base::loadLe<std::uint32_t>(chunk);
        binOffset = at + 8;
        if (base::loadLe<std::uint32_t>(chunk + 4) != 0x004E4942u ||
            binBytes > fileBytes_ - binOffset)
          fail(path, "GLB BIN chunk runs past the end of the file");
      }
    } else if (remote_) {
      json.resize(static_cast<std::size_t>(fileBytes_));
      readAt(0, json.data(), json.size());
    } else {
      if (fileBytes_ > kMaxJsonBytes) fail(path, "glTF JSON larger than 64 MiB");
      json = file_->head(static_cast<std::size_t>(kMaxJsonBytes));
    }
    try {
      open(json, glb, binOffset, binBytes);
    } catch (const gltf::Error& e) {
      throw FormatError(e.what());
    }
  }
  /// The columns of a remote GLB or .gltf (remote_): one splat primitive instance whose
  /// accessors lie tightly packed in the BIN chunk or buffer files, each read by its own
  /// range (COLOR_0 only where it is the colour); else NotPiecewiseError.
  void planColumns() {
    const auto refuse = [&](const std::string& why) {
      throw NotPiecewiseError(path_ + ": not read by columns: " + why);
    };
    if (primitives_.size() != 1) refuse(std::to_string(primitives_.size()) + " splat primitives");
    const SplatPrimitive& p = primitives_.front();
    for (const PieceAccessor* a : accessorsOf(p)) {
      const BufferSource& s = sources_[static_cast<std::size_t>(a->buffer)];
      if (s.memory) refuse("an accessor in a data: buffer");
      if (a->stride != a->elementBytes) refuse("an interleaved accessor");
      columns_.push_back(Column{s.offset + a->offset, a->count * a->elementBytes, a->elementBytes,
                                false, s.uri, s.uri.empty() ? 0 : s.byteLength, false, 0, false,
                                0});
    }
    // The whole reader loads (and checks the size of) every buffer file: one that no
    // column reads is left to it.
    for (const BufferSource& s : sources_)
      if (!s.uri.empty() && std::none_of(columns_.begin(), columns_.end(),
                                         [&](const Column& c) { return c.file == s.uri; }))
        refuse("a buffer file no splat attribute reads (" + s.uri + ")");
  }
  /// The accessors of `p` in the order of its columns.
  static std::vector<const PieceAccessor*> accessorsOf(const SplatPrimitive& p) {
    std::vector<const PieceAccessor*> all{&p.position, &p.rotation, &p.scale, &p.opacity, &p.color};
    for (const PieceAccessor& r : p.rest) all.push_back(&r);
    return all;
  }

 private:
  /// The JSON parsed with its file buffers emptied, the buffers' sources found, and the
  /// default scene's splat primitives planned.
  void open(const std::string& json, bool glb, std::uint64_t binOffset, std::uint64_t binBytes) {
    gltf::checkJsonDepth(json, path_);
    nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) fail(path_, "glTF JSON cannot be parsed");
    for (const char* compressed : {"KHR_draco_mesh_compression", "EXT_meshopt_compression"}) {
      bool named = json.find(compressed) != std::string::npos;
      for (const char* list : {"extensionsUsed", "extensionsRequired"})
        if (const auto it = doc.find(list); it != doc.end() && it->is_array())
          for (const nlohmann::json& e : *it)
            named |= e.is_string() && e.get<std::string>() == compressed;
      if (named)
        throw NotPiecewiseError(path_ + ": " + detail::kPiecewiseFormats +
                                ", not a glTF scene of compressed buffers (" + compressed + ")");
    }
    // Images are never read here; tinygltf would index their buffer views' placeholders.
    doc.erase("images");
    // Each file buffer's length and uri kept; in the JSON tinygltf parses it holds nothing.
    std::vector<std::pair<std::uint64_t, std::string>> files;  // byteLength, uri ("" = BIN)
    if (auto buffers = doc.find("buffers"); buffers != doc.end() && buffers->is_array()) {
      for (nlohmann::json& b : *buffers) {
        if (!b.is_object()) fail(path_, "a buffer is not an object");
        const auto length = b.find("byteLength");
        if (length == b.end() || !length->is_number_unsigned())
          fail(path_, "a buffer lacks its byteLength");
        const auto uri = b.find("uri");
        const std::string u = uri != b.end() && uri->is_string() ? uri->get<std::string>() : "";
        files.emplace_back(length->get<std::uint64_t>(), u);
        if (!u.starts_with("data:"))
          b = nlohmann::json{{"byteLength", 4}, {"uri", kPlaceholderBuffer}};
      }
    }
    model_ = gltf::load(doc.dump(), path_, nullptr);
    std::uint64_t budget = fileBytes_;
    std::set<std::string> counted;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const auto& [byteLength, uri] = files[i];
      BufferSource& s = sources_.emplace_back();
      s.byteLength = byteLength;
      if (uri.starts_with("data:")) {
        s.memory = &model_.buffers[i].data;
        if (s.memory->size() < byteLength) fail(path_, "buffer " + std::to_string(i) + " is short");
      } else if (uri.empty()) {
        if (!glb || i != 0) fail(path_, "buffer " + std::to_string(i) + " has no uri");
        if (byteLength > binBytes) fail(path_, "the GLB BIN chunk is shorter than buffer 0");
        s.file = file_;
        s.offset = binOffset;
      } else {
        const std::string relative = base::percentDecode(uri);
        if (!isFileBesideScene(relative)) fail(path_, relative + ": not a file beside the scene");
        if (remote_) {  // fetched by its columns' range requests, beside the scene's URL
          s.uri = relative;
          if (counted.insert(relative).second)  // (saturating: a hostile byteLength)
            budget += std::min(byteLength, std::numeric_limits<std::uint64_t>::max() - budget);
          continue;
        }
        s.file = std::make_shared<detail::PieceFile>(
            (std::filesystem::path(path_).parent_path() / relative).string());
        if (s.file->size() != byteLength)
          fail(path_, relative + ": expected " + std::to_string(byteLength) + " bytes, got " +
                          std::to_string(s.file->size()));
        if (counted.insert(relative).second) budget += s.file->size();  // each file once
      }
    }
    const std::uint64_t limit = std::min<std::uint64_t>(budget, kMaxSplats);
    bool haveColorSpace = false;
    detail::forEachGltfSplatPrimitive(
        model_, path_,
        [&](const tinygltf::Primitive& prim, const tinygltf::Value& ext, const glm::dmat4& world) {
          if (primitives_.size() >= kMaxInstances)
            throw NotPiecewiseError(path_ + ": " + detail::kPiecewiseFormats +
                                    ", not a glTF scene of more than " +
                                    std::to_string(kMaxInstances) + " splat primitive instances");
          SplatPrimitive p;
          p.attributes = detail::gltfSplatAttributes(prim, ext, path_);
          if (haveColorSpace && p.attributes.colorSpace != colorSpace_)
            fail(path_, "primitives differ in colorSpace");
          colorSpace_ = p.attributes.colorSpace;
          haveColorSpace = true;
          p.position = accessor(p.attributes.position, 3, "POSITION");
          p.count = p.position.count;
          if (p.count == 0) return;
          if (p.count > limit - std::min(limit, total_))
            fail(path_, "more splats than the file's bytes can hold (instanced " +
                            std::to_string(p.count) + " more)");
          p.rotation = accessor(p.attributes.rotation, 4, "ROTATION", p.count);
          p.scale = accessor(p.attributes.scale, 3, "SCALE", p.count);
          p.opacity = accessor(p.attributes.opacity, 1, "OPACITY", p.count);
          if (p.attributes.dc >= 0) {
            p.color = accessor(p.attributes.dc, 3, "SH_DEGREE_0_COEF_0", p.count);
          } else {
            p.color = accessor(p.attributes.color, 0, "COLOR_0", p.count);
            // glTF 2.0 section 3.7.2.1: COLOR_0 is VEC3 or VEC4 (the red, green and blue read).
            if (p.color.components != 3 && p.color.components != 4)
              fail(path_, "COLOR_0: expected VEC3 or VEC4, got " +
                              std::to_string(p.color.components) + " components");
          }
          for (int a : p.attributes.rest)
            p.rest.push_back(accessor(a, 3, "SH coefficient", p.count));
          p.placement =
              std::make_shared<const detail::GltfPlacement>(world, p.attributes.degree, path_);
          p.first = total_;
          total_ += p.count;
          degree_ = std::max(degree_, p.attributes.degree);
          primitives_.push_back(std::move(p));
        });
    if (total_ == 0)
      fail(path_, "no KHR_gaussian_splatting primitive with splats in the default scene");
  }

  /// Accessor `index` checked against its buffer's byteLength: `components` per element
  /// (0: any), `count` elements when not 0. Sparse accessors are not read piecewise.
  PieceAccessor accessor(int index, int components, const char* what, std::uint64_t count = 0) {
    const std::string where = std::string(what) + " accessor " + std::to_string(index);
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
      fail(path_, where + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse)
      throw NotPiecewiseError(path_ + ": " + detail::kPiecewiseFormats +
                              ", not a glTF scene of sparse accessors (" + where + ")");
    PieceAccessor p;
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    p.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (size <= 0 || p.components <= 0) fail(path_, where + " has an invalid type");
    if (components != 0 && p.components != components)
      fail(path_, where + " has " + std::to_string(p.components) + " components, expected " +
                      std::to_string(components));
    p.componentType = a.componentType;
    p.normalized = a.normalized;
    p.count = a.count;
    if (p.count > kMaxSplats)
      fail(path_, where + " has " + std::to_string(p.count) + " elements, more than " +
                      std::to_string(kMaxSplats));
    if (count != 0 && p.count != count)
      fail(path_, std::string(what) + ": expected " + std::to_string(count) + " elements, got " +
                      std::to_string(p.count));
    p.elementBytes = static_cast<std::size_t>(size) * static_cast<std::size_t>(p.components);
    p.stride = p.elementBytes;
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
      fail(path_, where + " has no valid bufferView");  // as the whole reader
    const tinygltf::BufferView& v = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= sources_.size())
      fail(path_, where + ": buffer " + std::to_string(v.buffer) + " does not exist");
    if (v.byteStride != 0) p.stride = v.byteStride;
    if (p.stride < p.elementBytes || p.stride > 252)  // glTF 2.0 clause 5.11: 4 to 252
      fail(path_, where + ": byteStride " + std::to_string(p.stride) + " out of range");
    const BufferSource& s = sources_[static_cast<std::size_t>(v.buffer)];
    if (v.byteOffset > s.byteLength || v.byteLength > s.byteLength - v.byteOffset)
      fail(path_, where + ": its buffer view runs past the end of its buffer");
    if (p.count > 0 && (a.byteOffset > v.byteLength ||
                        (p.count - 1) * p.stride + p.elementBytes > v.byteLength - a.byteOffset))
      fail(path_, where + " runs past the end of its buffer view");
    p.buffer = v.buffer;
    p.offset = v.byteOffset + a.byteOffset;
    return p;
  }

  /// Elements [from, from + n) of `a` as floats, `a.components` each: from `record` (its
  /// element `from`, tightly packed) when given, else from its buffer.
  void floats(const PieceAccessor& a, std::uint64_t from, std::size_t n, std::vector<float>& out,
              const char* record = nullptr) const {
    out.assign(n * static_cast<std::size_t>(a.components), 0.0f);
    if (n == 0) return;
    const BufferSource& s = sources_[static_cast<std::size_t>(a.buffer)];
    const std::size_t bytes = (n - 1) * a.stride + a.elementBytes;
    const std::uint64_t at = a.offset + from * a.stride;
    const unsigned char* data = nullptr;
    if (record) {
      data = reinterpret_cast<const unsigned char*>(record);
    } else if (s.memory) {
      data = s.memory->data() + at;
    } else {
      bytes_.resize(bytes);
      s.file->read(s.offset + at, bytes_.data(), bytes);
      data = reinterpret_cast<const unsigned char*>(bytes_.data());
    }
    const gltf::AccessorView v{data, n, a.stride, a.componentType, a.components, a.normalized};
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < a.components; ++c)
        out[i * static_cast<std::size_t>(a.components) + static_cast<std::size_t>(c)] =
            v.value(i, c);
  }

  /// Splats [from, from + n) of primitive `p` into `batch` from splat `at` on, from its
  /// accessors' buffers, or from `records` (its columns' records of them) when given.
  void place(const SplatPrimitive& p, std::uint64_t from, std::size_t n, GaussianCloud& batch,
             std::size_t at, const std::vector<const char*>* records) const {
    const auto record = [&](std::size_t k) { return records ? (*records)[k] : nullptr; };
    floats(p.position, from, n, pos_, record(0));
    floats(p.rotation, from, n, rot_, record(1));
    floats(p.scale, from, n, scale_, record(2));
    floats(p.opacity, from, n, opacity_, record(3));
    floats(p.color, from, n, color_, record(4));
    const auto cc = static_cast<std::size_t>(p.color.components);
    if (p.attributes.dc < 0)  // COLOR_0: the DC coefficient of its red, green and blue
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t k = 0; k < 3; ++k)
          color_[i * cc + k] = detail::dcOfColor(color_[i * cc + k]);
    rest_.resize(p.rest.size());
    for (std::size_t k = 0; k < p.rest.size(); ++k)
      floats(p.rest[k], from, n, rest_[k], record(5 + k));
    std::vector<const float*> restAt(p.rest.size());
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < p.rest.size(); ++k) restAt[k] = rest_[k].data() + i * 3;
      p.placement->place(&pos_[i * 3], &rot_[i * 4], &scale_[i * 3], opacity_[i], &color_[i * cc],
                         restAt.data(), batch, at + i);
    }
  }

  std::string path_;
  std::shared_ptr<detail::PieceFile> file_;  // null for a remote GLB's head
  std::uint64_t fileBytes_ = 0;
  bool remote_ = false;
  std::vector<Column> columns_;  // a remote GLB's (planColumns)
  tinygltf::Model model_;
  std::vector<BufferSource> sources_;
  std::vector<SplatPrimitive> primitives_;
  std::uint64_t total_ = 0, next_ = 0;
  int degree_ = 0;
  ColorSpace colorSpace_ = ColorSpace::srgb;
  // Scratch of one batch (mutable: decode() is const, called on one thread at a time).
  mutable std::vector<char> bytes_;
  mutable std::vector<float> pos_, rot_, scale_, opacity_, color_;
  mutable std::vector<std::vector<float>> rest_;
};

}  // namespace

std::unique_ptr<GaussianBatchReader> openGltfGaussianBatches(const std::string& path) {
  return std::make_unique<GltfGaussianBatches>(path);
}

GaussianColumns openGltfColumns(std::string_view head, const std::string& name,
                                std::uint64_t fileBytes) {
  GaussianColumns found;
  try {
    found.decoder = std::make_unique<GltfGaussianBatches>(name, head, fileBytes);
  } catch (const NeedMoreBytes&) {
    found.needMore = true;
  } catch (const NotPiecewiseError&) {
  } catch (const gltf::Error& e) {
    throw FormatError(e.what());
  }
  return found;
}

}  // namespace gs::splats
