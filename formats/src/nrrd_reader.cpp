// NRRD headers (teem's format definition, http://teem.sourceforge.net/nrrd/format.html)
// and their data: raw, gzip (decompressed by the caller) and ascii encodings.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <fast_float/fast_float.h>

#include "formats/volume_readers.hpp"

namespace gs::formats {

namespace {

// `s` made printable and short for an error message.
std::string shown(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 60))
    out +=
        (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) ? '?' : c;
  if (s.size() > 60) out += "...";
  return out;
}

[[noreturn]] void failAt(const std::string& name, std::size_t line, const std::string& what) {
  throw InputError(name + ":" + std::to_string(line) + ": " + what);
}

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

// Lower case with every run of white space made one space ("unsigned  Short" ->
// "unsigned short").
std::string normalized(std::string_view s) {
  std::string out;
  for (char c : trim(s)) {
    if (isSpace(c)) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

bool parseDouble(std::string_view tok, double& out) {
  if (tok.starts_with('+')) tok.remove_prefix(1);
  if (tok.empty()) return false;
  const auto r = fast_float::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

bool parseU64(std::string_view tok, std::uint64_t& out) {
  if (tok.starts_with('+')) tok.remove_prefix(1);
  if (tok.empty()) return false;
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

bool parseI64(std::string_view tok, std::int64_t& out) {
  if (tok.starts_with('+')) tok.remove_prefix(1);
  if (tok.empty()) return false;
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

struct TypeAlias {
  std::string_view name;
  ScalarType type;
};

// Every spelling teem's nrrdType enum accepts (normalized: lower case, single spaces).
constexpr std::array<TypeAlias, 42> kNrrdTypes{{
    {"signed char", ScalarType::int8},
    {"int8", ScalarType::int8},
    {"int8_t", ScalarType::int8},
    {"uchar", ScalarType::uint8},
    {"unsigned char", ScalarType::uint8},
    {"uint8", ScalarType::uint8},
    {"uint8_t", ScalarType::uint8},
    {"short", ScalarType::int16},
    {"short int", ScalarType::int16},
    {"signed short", ScalarType::int16},
    {"signed short int", ScalarType::int16},
    {"int16", ScalarType::int16},
    {"int16_t", ScalarType::int16},
    {"ushort", ScalarType::uint16},
    {"unsigned short", ScalarType::uint16},
    {"unsigned short int", ScalarType::uint16},
    {"uint16", ScalarType::uint16},
    {"uint16_t", ScalarType::uint16},
    {"int", ScalarType::int32},
    {"signed int", ScalarType::int32},
    {"int32", ScalarType::int32},
    {"int32_t", ScalarType::int32},
    {"uint", ScalarType::uint32},
    {"unsigned int", ScalarType::uint32},
    {"uint32", ScalarType::uint32},
    {"uint32_t", ScalarType::uint32},
    {"longlong", ScalarType::int64},
    {"long long", ScalarType::int64},
    {"long long int", ScalarType::int64},
    {"signed long long", ScalarType::int64},
    {"signed long long int", ScalarType::int64},
    {"int64", ScalarType::int64},
    {"int64_t", ScalarType::int64},
    {"ulonglong", ScalarType::uint64},
    {"unsigned long long", ScalarType::uint64},
    {"unsigned long long int", ScalarType::uint64},
    {"uint64", ScalarType::uint64},
    {"uint64_t", ScalarType::uint64},
    {"float", ScalarType::float32},
    {"double", ScalarType::float64},
    {"float32", ScalarType::float32},
    {"float64", ScalarType::float64},
}};

// dims.x * dims.y * dims.z after checking each is >= 1 and the product is <= kMaxVoxels.
std::size_t checkedVoxels(const glm::uvec3& d, const std::string& where,
                          std::uint64_t limit = kMaxVoxels) {
  if (d.x == 0 || d.y == 0 || d.z == 0)
    throw InputError(where + ": expected sizes >= 1, got " + std::to_string(d.x) + " " +
                     std::to_string(d.y) + " " + std::to_string(d.z));
  const std::uint64_t xy = std::uint64_t{d.x} * d.y;
  if (xy > limit || xy * d.z > limit)
    throw InputError(where + ": volume of " + std::to_string(d.x) + " x " + std::to_string(d.y) +
                     " x " + std::to_string(d.z) + " voxels exceeds the limit of " +
                     std::to_string(limit) + " voxels");
  return static_cast<std::size_t>(xy * d.z);
}

// A spacing as a Volume wants it: finite and > 0 (nan and 0 mean "unknown": 1).
float usableSpacing(double s) {
  s = std::fabs(s);
  if (!std::isfinite(s) || s == 0.0 || s > std::numeric_limits<float>::max()) return 1.0f;
  const float f = static_cast<float>(s);
  return f > 0.0f ? f : 1.0f;
}

// "(1,0,0) none (0,0,2.5)": one entry per vector, empty for "none".
std::vector<std::vector<double>> parseVectors(std::string_view value, const std::string& name,
                                              std::size_t line) {
  std::vector<std::vector<double>> out;
  std::size_t i = 0;
  while (true) {
    while (i < value.size() && isSpace(value[i])) ++i;
    if (i == value.size()) break;
    const std::string_view rest = value.substr(i);
    if (normalized(rest.substr(0, 4)) == "none" && (rest.size() == 4 || isSpace(rest[4]))) {
      out.emplace_back();
      i += 4;
      continue;
    }
    const std::size_t close = rest.find(')');
    if (rest.front() != '(' || close == std::string_view::npos)
      failAt(name, line, "expected a vector '(x,y,z)' or 'none', got '" + shown(rest) + "'");
    std::vector<double> v;
    std::string_view inner = rest.substr(1, close - 1);
    while (true) {
      const std::size_t comma = inner.find(',');
      const std::string_view tok = trim(inner.substr(0, comma));
      double x = 0.0;
      if (!parseDouble(tok, x))
        failAt(name, line, "expected a vector component, got '" + shown(tok) + "'");
      v.push_back(x);
      if (comma == std::string_view::npos) break;
      inner.remove_prefix(comma + 1);
    }
    out.push_back(std::move(v));
    i += close + 1;
  }
  return out;
}

struct Field {
  std::string_view value;
  std::size_t line = 0;
  bool present() const { return line != 0; }
};

// FORMAT with its one integer conversion (%d, %i, %u with an optional 0 flag and width)
// applied to `i`; "%%" is a literal '%'. Empty when FORMAT has not exactly one.
std::string formatFileName(std::string_view format, std::int64_t i, bool& ok) {
  std::string out;
  int conversions = 0;
  ok = false;
  for (std::size_t k = 0; k < format.size(); ++k) {
    if (format[k] != '%') {
      out += format[k];
      continue;
    }
    if (++k == format.size()) return {};
    if (format[k] == '%') {
      out += '%';
      continue;
    }
    bool zero = false;
    if (format[k] == '0') zero = true, ++k;
    std::size_t width = 0;
    while (k < format.size() && format[k] >= '0' && format[k] <= '9' && width < 100)
      width = width * 10 + static_cast<std::size_t>(format[k++] - '0');
    if (k == format.size() || (format[k] != 'd' && format[k] != 'i' && format[k] != 'u') ||
        width > 32)
      return {};
    ++conversions;
    std::string digits = std::to_string(i < 0 ? -i : i);
    const std::string sign = i < 0 ? "-" : "";
    const std::size_t used = digits.size() + sign.size();
    if (used < width)
      digits = zero ? sign + std::string(width - used, '0') + digits
                    : std::string(width - used, ' ') + sign + digits;
    else
      digits = sign + digits;
    out += digits;
  }
  ok = conversions == 1;
  return out;
}

// The multi-file forms of "data file:" (teem's format definition, section 3):
//   LIST [SUBDIM], the names following on their own lines, or
//   FORMAT MIN MAX STEP [SUBDIM].
void parseMultiFile(NrrdHeader& h, const std::vector<std::string_view>& w,
                    std::vector<std::string> listed, const std::vector<std::uint64_t>& size,
                    const std::string& name, std::size_t line, const NrrdParseOptions& options) {
  const bool isList = w.front() == "LIST";
  const std::size_t dim = size.size();
  std::uint64_t subdim = dim - 1;
  const std::size_t subdimAt = isList ? 1 : 4;
  if (!isList && w.size() < 4)
    failAt(name, line,
           "expected 'data file: FORMAT MIN MAX STEP [SUBDIM]', got " + std::to_string(w.size()) +
               " words");
  if (w.size() > subdimAt + 1)
    failAt(name, line,
           "expected at most " + std::to_string(subdimAt + 1) + " words after 'data file:', got " +
               std::to_string(w.size()));
  if (w.size() == subdimAt + 1 && (!parseU64(w[subdimAt], subdim) || subdim < 1 || subdim > dim))
    failAt(name, line,
           "expected a data file dimension between 1 and " + std::to_string(dim) + ", got '" +
               shown(w[subdimAt]) + "'");
  std::uint64_t perFile = 1, total = 1;
  for (std::size_t i = 0; i < dim; ++i) {
    total *= size[i];
    if (i < subdim) perFile *= size[i];
  }
  const std::uint64_t expected = total / perFile;
  if (isList) {
    h.dataFiles = std::move(listed);
  } else {
    std::int64_t lo = 0, hi = 0, step = 0;
    if (!parseI64(w[1], lo) || !parseI64(w[2], hi) || !parseI64(w[3], step) || step == 0)
      failAt(name, line,
             "expected integers MIN MAX STEP (STEP not 0), got '" + shown(w[1]) + " " +
                 shown(w[2]) + " " + shown(w[3]) + "'");
    if ((step > 0 && hi < lo) || (step < 0 && hi > lo))
      failAt(name, line,
             "data file range " + std::to_string(lo) + " to " + std::to_string(hi) + " step " +
                 std::to_string(step) + " names no file");
    // |hi - lo| < 2^64 as both are int64; compute in unsigned to avoid overflow.
    const std::uint64_t span =
        step > 0 ? static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo)
                 : static_cast<std::uint64_t>(lo) - static_cast<std::uint64_t>(hi);
    const std::uint64_t stride = step > 0 ? static_cast<std::uint64_t>(step)
                                          : std::uint64_t{0} - static_cast<std::uint64_t>(step);
    const std::uint64_t count = span / stride + 1;
    if (count != expected)
      failAt(name, line,
             "data file range names " + std::to_string(count) + " files, expected " +
                 std::to_string(expected) + " (one per " + std::to_string(subdim) +
                 "-dimensional part of the data)");
    if (count > options.maxDataFiles)
      failAt(name, line, "more than " + std::to_string(options.maxDataFiles) + " data files");
    for (std::uint64_t k = 0; k < count; ++k) {
      bool ok = false;
      // In [lo, hi]; unsigned arithmetic so that no intermediate overflows.
      const std::int64_t i = static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) +
                                                       k * static_cast<std::uint64_t>(step));
      h.dataFiles.push_back(formatFileName(w[0], i, ok));
      if (!ok)
        failAt(name, line,
               "expected a data file format with one integer conversion (%d, %03d), "
               "got '" +
                   shown(w[0]) + "'");
    }
  }
  if (h.dataFiles.size() != expected)
    failAt(name, line,
           "data file list names " + std::to_string(h.dataFiles.size()) + " files, expected " +
               std::to_string(expected) + " (one per " + std::to_string(subdim) +
               "-dimensional part of the data)");
  for (const std::string& f : h.dataFiles)
    if (f.empty()) failAt(name, line, "expected a data file name, got ''");
  h.samplesPerDataFile = perFile;
}

}  // namespace

NrrdHeader parseNrrdHeader(std::string_view bytes, const std::string& name,
                           const NrrdParseOptions& options) {
  // Magic line.
  std::size_t eol = bytes.find('\n');
  std::string_view magic = bytes.substr(0, eol);
  if (magic.ends_with('\r')) magic.remove_suffix(1);
  if (magic.size() != 8 || !magic.starts_with("NRRD000") || magic[7] < '1' || magic[7] > '5')
    failAt(name, 1, "expected the NRRD magic 'NRRD0001'..'NRRD0005', got '" + shown(magic) + "'");

  NrrdHeader h;
  Field type, dimension, sizes, spacings, directions, origin, endian, encoding, dataFile, lineSkip,
      byteSkip;
  std::size_t pos = eol == std::string_view::npos ? bytes.size() : eol + 1;
  std::size_t lineNo = 1;
  h.dataOffset = bytes.size();
  bool listing = false;  // after "data file: LIST": every line is a file name
  std::vector<std::string> listed;
  while (pos < bytes.size()) {
    eol = bytes.find('\n', pos);
    const std::size_t next = eol == std::string_view::npos ? bytes.size() : eol + 1;
    std::string_view line = bytes.substr(pos, next - pos);
    if (line.ends_with('\n')) line.remove_suffix(1);
    if (line.ends_with('\r')) line.remove_suffix(1);
    pos = next;
    ++lineNo;
    if (line.empty()) {  // the blank line: attached data follow
      h.dataOffset = pos;
      break;
    }
    if (listing) {
      if (listed.size() >= options.maxDataFiles)
        failAt(name, lineNo,
               "more than " + std::to_string(options.maxDataFiles) + " data files listed");
      listed.emplace_back(trim(line));
      continue;
    }
    if (line.front() == '#') continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos)
      failAt(name, lineNo, "expected 'field: value', got '" + shown(line) + "'");
    if (colon + 1 < line.size() && line[colon + 1] == '=') continue;  // key:=value
    const std::string key = normalized(line.substr(0, colon));
    const Field f{line.substr(colon + 1), lineNo};
    if (key == "type")
      type = f;
    else if (key == "dimension")
      dimension = f;
    else if (key == "sizes")
      sizes = f;
    else if (key == "spacings")
      spacings = f;
    else if (key == "space directions")
      directions = f;
    else if (key == "space origin")
      origin = f;
    else if (key == "endian")
      endian = f;
    else if (key == "encoding")
      encoding = f;
    else if (key == "data file" || key == "datafile") {
      dataFile = f;
      // The LIST form names one file per following line: stop before reading them.
      const auto w = words(f.value);
      if (!w.empty() && w.front() == "LIST") {
        if (!options.multiFile)
          failAt(name, lineNo, "data file lists ('data file: LIST') are not supported");
        listing = true;
      }
    } else if (key == "line skip" || key == "lineskip")
      lineSkip = f;
    else if (key == "byte skip" || key == "byteskip")
      byteSkip = f;
    // Other fields (content, kinds, labels, units, space, centers, ...) do not matter here.
  }

  for (const auto& [field, fieldName] :
       {std::pair{&type, "type"}, std::pair{&dimension, "dimension"}, std::pair{&sizes, "sizes"},
        std::pair{&encoding, "encoding"}})
    if (!field->present())
      throw InputError(name + ": missing required NRRD field '" + fieldName + "'");

  // type
  {
    const std::string t = normalized(type.value);
    const auto it = std::find_if(kNrrdTypes.begin(), kNrrdTypes.end(),
                                 [&](const TypeAlias& a) { return a.name == t; });
    if (t == "block") failAt(name, type.line, "unsupported NRRD type 'block'");
    if (it == kNrrdTypes.end())
      failAt(name, type.line,
             "expected a NRRD type (int8, uint8, int16, uint16, int32, uint32, int64, uint64, "
             "float, double), got '" +
                 shown(trim(type.value)) + "'");
    h.type = it->type;
  }

  // dimension and sizes, and which axes are x, y, z (-1: absent, size 1).
  std::uint64_t dim = 0;
  if (!parseU64(trim(dimension.value), dim) || dim < 2 || dim > 4)
    failAt(name, dimension.line,
           "expected dimension 2, 3 or 4, got '" + shown(trim(dimension.value)) + "'");
  const auto sizeWords = words(sizes.value);
  if (sizeWords.size() != dim)
    failAt(name, sizes.line,
           "expected " + std::to_string(dim) + " sizes, got " + std::to_string(sizeWords.size()));
  std::vector<std::uint64_t> size(dim);
  for (std::size_t i = 0; i < dim; ++i) {
    if (!parseU64(sizeWords[i], size[i]) || size[i] == 0)
      failAt(name, sizes.line, "expected a size >= 1, got '" + shown(sizeWords[i]) + "'");
    if (size[i] > std::numeric_limits<std::uint32_t>::max())
      failAt(name, sizes.line, "expected a size below 2^32, got '" + shown(sizeWords[i]) + "'");
  }
  std::array<int, 3> axis{0, 1, 2};
  if (dim == 2) {
    axis = {0, 1, -1};
  } else if (dim == 4) {
    if (size[0] == 1) {
      axis = {1, 2, 3};
    } else if (options.componentAxis && size[0] <= 4) {
      axis = {1, 2, 3};
      h.components = static_cast<std::uint32_t>(size[0]);
    } else if (size[3] != 1)
      failAt(name, sizes.line,
             "expected a 4-dimensional NRRD to have one axis of size 1 (first or last), got "
             "sizes '" +
                 shown(trim(sizes.value)) + "'");
  }
  for (int i = 0; i < 3; ++i)
    h.dims[i] = axis[i] < 0 ? 1u : static_cast<std::uint32_t>(size[axis[i]]);
  if (static_cast<std::uint64_t>(h.dims.x) * h.components >
      std::numeric_limits<std::uint32_t>::max())
    failAt(name, sizes.line, "expected sizes below 2^32, got '" + shown(trim(sizes.value)) + "'");
  h.dims.x *= h.components;
  checkedVoxels(h.dims, name + ":" + std::to_string(sizes.line), options.maxVoxels);

  if (spacings.present()) {
    const auto w = words(spacings.value);
    if (w.size() != dim)
      failAt(name, spacings.line,
             "expected " + std::to_string(dim) + " spacings, got " + std::to_string(w.size()));
    for (int i = 0; i < 3; ++i) {
      if (axis[i] < 0) continue;
      double s = 0.0;
      if (!parseDouble(w[axis[i]], s))
        failAt(name, spacings.line, "expected a spacing, got '" + shown(w[axis[i]]) + "'");
      h.spacing[i] = usableSpacing(s);
    }
  }
  if (directions.present()) {
    const auto v = parseVectors(directions.value, name, directions.line);
    if (v.size() != dim)
      failAt(
          name, directions.line,
          "expected " + std::to_string(dim) + " space directions, got " + std::to_string(v.size()));
    for (int i = 0; i < 3; ++i) {
      if (axis[i] < 0 || v[axis[i]].empty()) continue;
      double len2 = 0.0;
      for (double c : v[axis[i]]) len2 += c * c;
      h.spacing[i] = usableSpacing(std::sqrt(len2));
    }
  }
  if (origin.present()) {
    const auto v = parseVectors(origin.value, name, origin.line);
    if (v.size() != 1 || v[0].empty())
      failAt(name, origin.line,
             "expected one vector '(x,y,z)', got '" + shown(trim(origin.value)) + "'");
    for (std::size_t i = 0; i < 3 && i < v[0].size(); ++i)
      h.origin[static_cast<int>(i)] = std::isfinite(v[0][i]) ? static_cast<float>(v[0][i]) : 0.0f;
  }
  if (endian.present()) {
    const std::string e = normalized(endian.value);
    if (e != "little" && e != "big")
      failAt(name, endian.line,
             "expected endian 'little' or 'big', got '" + shown(trim(endian.value)) + "'");
    h.bigEndian = e == "big";
  }
  {
    const std::string e = normalized(encoding.value);
    if (e == "raw")
      h.encoding = NrrdHeader::Encoding::raw;
    else if (e == "gzip" || e == "gz")
      h.encoding = NrrdHeader::Encoding::gzip;
    else if (e == "ascii" || e == "txt" || e == "text")
      h.encoding = NrrdHeader::Encoding::ascii;
    else if (e == "hex")
      h.encoding = NrrdHeader::Encoding::hex;
    else if (e == "bzip2" || e == "bz2" || e == "zrl")
      failAt(name, encoding.line, "unsupported NRRD encoding '" + e + "'");
    else
      failAt(name, encoding.line,
             "expected a NRRD encoding (raw, gzip, ascii, hex), got '" +
                 shown(trim(encoding.value)) + "'");
  }
  if (dataFile.present()) {
    const std::string_view f = trim(dataFile.value);
    const auto w = words(f);
    if (f.empty()) failAt(name, dataFile.line, "expected a data file name, got ''");
    const bool isList = w.front() == "LIST";
    const bool isFormat = w.size() > 1 && w.front().find('%') != std::string_view::npos;
    if (isFormat && !options.multiFile)
      failAt(name, dataFile.line,
             "data file patterns ('" + shown(f) + "') are not supported; use a single file");
    if (isList || isFormat)
      parseMultiFile(h, w, std::move(listed), size, name, dataFile.line, options);
    else
      h.dataFile = std::string(f);
  }
  if (lineSkip.present()) {
    std::uint64_t n = 0;
    if (!parseU64(trim(lineSkip.value), n) || n > std::numeric_limits<std::size_t>::max())
      failAt(name, lineSkip.line,
             "expected a line skip >= 0, got '" + shown(trim(lineSkip.value)) + "'");
    h.lineSkip = static_cast<std::size_t>(n);
  }
  if (byteSkip.present()) {
    std::int64_t n = 0;
    if (!parseI64(trim(byteSkip.value), n) || n < -1)
      failAt(name, byteSkip.line,
             "expected a byte skip >= -1, got '" + shown(trim(byteSkip.value)) + "'");
    if (n == -1 && h.encoding == NrrdHeader::Encoding::ascii)
      failAt(name, byteSkip.line, "expected byte skip -1 only with raw or gzip encoding");
    h.byteSkip = n;
  }
  return h;
}

std::string_view skipNrrdLines(std::string_view bytes, std::size_t lines, const std::string& name) {
  std::size_t pos = 0;
  for (std::size_t i = 0; i < lines; ++i) {
    const std::size_t end = bytes.find_first_of("\r\n", pos);
    if (end == std::string_view::npos)
      throw InputError(name + ": expected " + std::to_string(lines) + " lines to skip, got " +
                       std::to_string(i));
    pos = end + 1;
    if (bytes[end] == '\r' && pos < bytes.size() && bytes[pos] == '\n') ++pos;
  }
  return bytes.substr(pos);
}

namespace {

/// The bytes of hex-encoded data: pairs of hexadecimal digits, white space between them
/// skipped, at most `need` bytes (the rest is ignored).
std::string decodeHex(std::string_view data, std::size_t need, const std::string& name) {
  const auto digit = [](char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  out.reserve(std::min(need, data.size() / 2 + 1));
  int high = -1;
  for (std::size_t i = 0; i < data.size() && out.size() < need; ++i) {
    if (isSpace(data[i])) continue;
    const int d = digit(data[i]);
    if (d < 0)
      throw InputError(name + ": expected a hexadecimal digit in hex data, got '" +
                       shown(data.substr(i, 1)) + "'");
    if (high < 0) {
      high = d;
    } else {
      out.push_back(static_cast<char>(high << 4 | d));
      high = -1;
    }
  }
  return out;
}

}  // namespace

Volume decodeNrrdData(const NrrdHeader& header, std::string_view data, const std::string& name) {
  if (header.encoding == NrrdHeader::Encoding::hex) {
    NrrdHeader raw = header;
    raw.encoding = NrrdHeader::Encoding::raw;
    // The byte skip applies to the decoded bytes: decode that many more.
    const std::size_t skip = header.byteSkip > 0 ? static_cast<std::size_t>(header.byteSkip) : 0;
    const std::string bytes =
        decodeHex(skipNrrdLines(data, header.lineSkip, name),
                  checkedVoxels(header.dims, name) * scalarBytes(header.type) + skip, name);
    raw.lineSkip = 0;
    return decodeNrrdData(raw, bytes, name);
  }
  const std::size_t count = checkedVoxels(header.dims, name);
  const std::size_t need = count * scalarBytes(header.type);
  const bool ascii = header.encoding == NrrdHeader::Encoding::ascii;
  if (header.encoding != NrrdHeader::Encoding::gzip)
    data = skipNrrdLines(data, header.lineSkip, name);
  if (header.byteSkip == -1 && !ascii) {
    if (data.size() < need)
      throw InputError(name + ": expected " + std::to_string(need) + " bytes of voxel data, got " +
                       std::to_string(data.size()));
    data = data.substr(data.size() - need);
  } else if (header.byteSkip < 0) {
    throw InputError(name + ": expected a byte skip >= 0" + std::string(ascii ? "" : " or -1") +
                     ", got " + std::to_string(header.byteSkip));
  } else {
    if (static_cast<std::uint64_t>(header.byteSkip) > data.size())
      throw InputError(name + ": byte skip of " + std::to_string(header.byteSkip) +
                       " bytes goes past the end of the " + std::to_string(data.size()) +
                       " bytes of data");
    data.remove_prefix(static_cast<std::size_t>(header.byteSkip));
  }

  if (!ascii) {
    RawLayout layout;
    layout.dims = header.dims;
    layout.type = header.type;
    layout.bigEndian = header.bigEndian;
    layout.spacing = header.spacing;
    Volume v = decodeRaw(data, layout, name);
    v.origin = header.origin;
    return v;
  }

  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(header.spacing[i]) || !(header.spacing[i] > 0.0f))
      throw InputError(name + ": expected spacings > 0, got " + std::to_string(header.spacing[i]));
  Volume v;
  v.dims = header.dims;
  v.spacing = header.spacing;
  v.origin = header.origin;
  v.sourceType = header.type;
  // Every value takes at least two bytes but the last, so this bounds the allocation by
  // the input size.
  v.samples.reserve(std::min(count, data.size() / 2 + 1));
  std::size_t i = 0;
  auto isSep = [](char c) { return isSpace(c) || c == ','; };
  while (v.samples.size() < count) {
    while (i < data.size() && isSep(data[i])) ++i;
    if (i == data.size()) break;
    const std::size_t start = i;
    while (i < data.size() && !isSep(data[i])) ++i;
    const std::string_view tok = data.substr(start, i - start);
    double x = 0.0;
    if (!parseDouble(tok, x))
      throw InputError(name + ": expected a number in ascii voxel data, got '" + shown(tok) + "'");
    v.samples.push_back(static_cast<float>(x));
  }
  if (v.samples.size() < count)
    throw InputError(name + ": expected " + std::to_string(count) +
                     " values of ascii voxel data, got " + std::to_string(v.samples.size()));
  return v;
}

}  // namespace gs::formats
