// TIFF and OME-TIFF volumes from bytes (formats/tiff_reader.hpp): the pages through
// tiff_io.hpp, the physical sizes and plane order from the OME-XML.
#include "formats/tiff_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "tiff_io.hpp"

namespace gs::formats {

namespace {

// The value of attribute `name` in the start tag `tag` (`name="v"` or `name='v'`, after a
// space); empty when absent.
std::string_view omeAttribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const bool startsWord = at > 0 && (tag[at - 1] == ' ' || tag[at - 1] == '\t' ||
                                       tag[at - 1] == '\n' || tag[at - 1] == '\r');
    std::size_t k = at + name.size();
    while (k < tag.size() && (tag[k] == ' ' || tag[k] == '\t')) ++k;
    if (!startsWord || k >= tag.size() || tag[k] != '=') continue;
    ++k;
    while (k < tag.size() && (tag[k] == ' ' || tag[k] == '\t')) ++k;
    if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
    const std::size_t end = tag.find(tag[k], k + 1);
    if (end == std::string_view::npos) return {};
    return tag.substr(k + 1, end - k - 1);
  }
  return {};
}

// Micrometres per unit of the OME UnitsLength symbol `unit` (0: not a length we take).
double omeMicrometresPer(std::string_view unit) {
  struct Unit {
    std::string_view symbol;
    double um;
  };
  static constexpr Unit kUnits[] = {
      {"\xC2\xB5m", 1.0},  // U+00B5 MICRO SIGN, OME's symbol
      {"\xCE\xBCm", 1.0},  // U+03BC GREEK SMALL LETTER MU
      {"um", 1.0},
      {"micron", 1.0},
      {"nm", 1e-3},
      {"pm", 1e-6},
      {"fm", 1e-9},
      {"am", 1e-12},
      {"zm", 1e-15},
      {"ym", 1e-18},
      {"\xC3\x85", 1e-4},      // U+00C5 Å
      {"\xE2\x84\xAB", 1e-4},  // U+212B ANGSTROM SIGN
      {"mm", 1e3},
      {"cm", 1e4},
      {"dm", 1e5},
      {"m", 1e6},
      {"dam", 1e7},
      {"hm", 1e8},
      {"km", 1e9},
      {"Mm", 1e12},
      {"Gm", 1e15},
      {"Tm", 1e18},
      {"Pm", 1e21},
      {"Em", 1e24},
      {"Zm", 1e27},
      {"Ym", 1e30},
      {"thou", 25.4},
      {"li", 25.4 * 250.0 / 3.0},
      {"in", 25400.0},
      {"ft", 304800.0},
      {"yd", 914400.0},
      {"mi", 1609344000.0},
  };
  for (const Unit& u : kUnits)
    if (u.symbol == unit) return u.um;
  return 0.0;
}

std::uint64_t omeSize(std::string_view text) {
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && ptr == text.data() + text.size() && v >= 1 && v <= (1u << 30) ? v : 1;
}

}  // namespace

std::uint64_t OmePixels::pageOfSlice(std::uint64_t z) const {
  std::uint64_t stride = 1;
  for (std::size_t i = 2; i < dimensionOrder.size(); ++i) {
    const char d = dimensionOrder[i];
    if (d == 'Z') break;
    stride *= d == 'C' ? sizeC : d == 'T' ? sizeT : 1;
  }
  return z * stride;
}

OmePixels parseOmeXml(std::string_view xml) {
  OmePixels ome;
  // The first Pixels start tag, with or without a namespace prefix.
  std::size_t at = std::string_view::npos;
  for (std::size_t k = xml.find("Pixels"); k != std::string_view::npos;
       k = xml.find("Pixels", k + 1)) {
    const bool afterOpen = k > 0 && (xml[k - 1] == '<' || xml[k - 1] == ':');
    const bool beforeSpace =
        k + 6 < xml.size() && (xml[k + 6] == ' ' || xml[k + 6] == '\n' || xml[k + 6] == '\t' ||
                               xml[k + 6] == '\r' || xml[k + 6] == '>' || xml[k + 6] == '/');
    if (afterOpen && beforeSpace) {
      at = k;
      break;
    }
  }
  if (at == std::string_view::npos) return ome;
  const std::size_t end = xml.find('>', at);
  const std::string_view tag = xml.substr(at, end == std::string_view::npos ? xml.npos : end - at);
  ome.found = true;
  static constexpr std::string_view kSize[] = {"PhysicalSizeX", "PhysicalSizeY", "PhysicalSizeZ"};
  static constexpr std::string_view kUnit[] = {"PhysicalSizeXUnit", "PhysicalSizeYUnit",
                                               "PhysicalSizeZUnit"};
  for (int i = 0; i < 3; ++i) {
    const std::string_view text = omeAttribute(tag, kSize[i]);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() ||
        !std::isfinite(v) || !(v > 0.0))
      continue;
    const std::string_view unit = omeAttribute(tag, kUnit[i]);
    const double um = unit.empty() ? 1.0 : omeMicrometresPer(unit);
    const double size = v * um;
    if (um > 0.0 && std::isfinite(size) && size > 0.0 && size < 1e30) {
      ome.spacing[i] = static_cast<float>(size);
      ome.hasSpacing[i] = ome.spacing[i] > 0.0f;
      if (!ome.hasSpacing[i]) ome.spacing[i] = 1.0f;
    }
  }
  ome.sizeZ = omeSize(omeAttribute(tag, "SizeZ"));
  ome.sizeC = omeSize(omeAttribute(tag, "SizeC"));
  ome.sizeT = omeSize(omeAttribute(tag, "SizeT"));
  const std::string_view order = omeAttribute(tag, "DimensionOrder");
  if (order.size() == 5 && order.starts_with("XY") && order.find('Z') != order.npos &&
      order.find('C') != order.npos && order.find('T') != order.npos)
    ome.dimensionOrder = std::string(order);
  return ome;
}

bool hasTiffMagic(std::string_view head) {
  return head.starts_with(std::string_view("II*\0", 4)) ||
         head.starts_with(std::string_view("MM\0*", 4)) ||
         head.starts_with(std::string_view("II+\0", 4)) ||
         head.starts_with(std::string_view("MM\0+", 4));
}

TiffVolume readTiff(std::string_view bytes, const std::string& name) {
  if (!hasTiffMagic(bytes))
    throw InputError(name +
                     ": not a TIFF file (expected 'II*', 'MM*' or BigTIFF's 'II+' at "
                     "byte 0)");
  detail::TiffFile tiff(bytes, name);
  TiffVolume out;
  out.pages = tiff.pages();
  if (out.pages == 0) throw InputError(name + ": a TIFF without pages");
  const std::string description = tiff.description();
  if (description.find("<OME") != std::string::npos ||
      description.find(":OME") != std::string::npos)
    out.ome = parseOmeXml(description);
  std::uint64_t slices = out.pages;
  if (out.ome.found) {
    const OmePixels& o = out.ome;
    const std::uint64_t planes = o.sizeZ * o.sizeC * o.sizeT;
    if (planes > out.pages)
      throw InputError(name + ": the OME-XML describes " + std::to_string(planes) +
                       " planes, the file has " + std::to_string(out.pages) +
                       " pages (multi-file OME-TIFF is not supported)");
    slices = o.sizeZ;
  }
  const detail::SliceShape shape = tiff.shape(0);
  Volume& v = out.volume;
  v.dims = {shape.width, shape.height, static_cast<std::uint32_t>(slices)};
  v.sourceType = shape.type;
  if (out.ome.found) v.spacing = out.ome.spacing;
  const std::uint64_t slice = std::uint64_t{shape.width} * shape.height;
  if (slice * slices > kMaxVoxels)
    throw InputError(name + ": " + std::to_string(slice * slices) + " voxels exceed the limit of " +
                     std::to_string(kMaxVoxels));
  // Page by page, each checked against the bytes it stores before it is allocated.
  for (std::uint64_t z = 0; z < slices; ++z) {
    const std::uint64_t page = out.ome.found ? out.ome.pageOfSlice(z) : z;
    tiff.checkStoredBytes(static_cast<std::uint32_t>(page), slice * scalarBytes(shape.type));
    v.samples.resize(static_cast<std::size_t>(slice * (z + 1)));
    tiff.read(static_cast<std::uint32_t>(page), shape,
              v.samples.data() + static_cast<std::size_t>(slice * z));
  }
  return out;
}

}  // namespace gs::formats
