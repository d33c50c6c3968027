// ElevationGrid (6.18) and Extrusion (6.19): both become a polygon soup of quadrilaterals
// over a grid of shared points (plus the Extrusion's caps) and go through
// buildPolygonMesh, so creaseAngle, ccw and degenerate quads behave as in IndexedFaceSet.
#include "geometry_internal.hpp"

#include "vrml/geo_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gs::vrml::geometry_detail {

namespace {

constexpr glm::vec4 kWhite(1.0f);

/// Appends one face of corners (point ids) when all its points are finite; returns false
/// (adding nothing) otherwise.
bool addFace(PolygonSoup& soup, std::initializer_list<std::uint32_t> ids) {
  for (std::uint32_t id : ids)
    if (!finite(soup.points[id])) return false;
  soup.corners.insert(soup.corners.end(), ids);
  soup.endFace();
  return true;
}

bool positiveSpacing(float v, const char* name, ProblemLog& log) {
  if (std::isfinite(v) && v > 0.0f) return true;
  log.add(std::string(name) + " must be > 0, got " + std::to_string(v) + "; not drawn");
  return false;
}

}  // namespace

glm::vec3 elevationGridPoint(double xSpacing, double zSpacing, std::size_t i, std::size_t j,
                             double height) {
  return {static_cast<float>(xSpacing * static_cast<double>(i)), static_cast<float>(height),
          static_cast<float>(zSpacing * static_cast<double>(j))};
}

std::vector<glm::vec3> elevationGridPoints(const Node& node, std::size_t count) {
  const std::int32_t xDim = node.get<FieldType::SFInt32>("xDimension", 0);
  const std::int32_t zDim = node.get<FieldType::SFInt32>("zDimension", 0);
  if (xDim < 1 || zDim < 1) return {};
  const double xSpacing = node.get<FieldType::SFFloat>("xSpacing", 1.0f);
  const double zSpacing = node.get<FieldType::SFFloat>("zSpacing", 1.0f);
  const auto& heights = fieldOr<FieldType::MFFloat>(node, "height");
  const auto nx = static_cast<std::size_t>(xDim);
  count = std::min(count, nx * static_cast<std::size_t>(zDim));
  std::vector<glm::vec3> points(count);
  for (std::size_t k = 0; k < count; ++k)
    points[k] = elevationGridPoint(xSpacing, zSpacing, k % nx, k / nx,
                                   k < heights.size() ? double{heights[k]} : 0.0);
  return points;
}

Mesh tessellateElevationGrid(const Node& node, ProblemLog& log) {
  // X3D's GeoElevationGrid (clause 25.4.3): the same grid in geo coordinates, its spacings
  // and heights doubles, each point converted to local coordinates (vrml/geo_nodes.hpp).
  const bool geo = node.typeId() == NodeTypeId::GeoElevationGrid;
  const std::int32_t xDim = node.get<FieldType::SFInt32>("xDimension", 0);
  const std::int32_t zDim = node.get<FieldType::SFInt32>("zDimension", 0);
  const double xSpacing = geo ? node.get<FieldType::SFDouble>("xSpacing", 1.0)
                              : node.get<FieldType::SFFloat>("xSpacing", 1.0f);
  const double zSpacing = geo ? node.get<FieldType::SFDouble>("zSpacing", 1.0)
                              : node.get<FieldType::SFFloat>("zSpacing", 1.0f);
  const auto& floatHeight = fieldOr<FieldType::MFFloat>(node, "height");
  const auto& doubleHeight = fieldOr<FieldType::MFDouble>(node, "height");
  const std::size_t heights = geo ? doubleHeight.size() : floatHeight.size();
  const auto height = [&](std::size_t k) {
    if (k >= heights) return 0.0;
    return geo ? doubleHeight[k] : static_cast<double>(floatHeight[k]);
  };
  if (xDim < 0 || zDim < 0) log.add("xDimension and zDimension must be >= 0");
  if (xDim < 2 || zDim < 2) return {};
  if (!positiveSpacing(static_cast<float>(xSpacing), "xSpacing", log) ||
      !positiveSpacing(static_cast<float>(zSpacing), "zSpacing", log))
    return {};

  // Heights missing at the end are 0, as X_ITE 15 reads them (an ElevationGrid without
  // heights is a flat grid), for grids up to kMaxElevationGridPoints; a larger grid uses
  // only the rows its height array really has (never trust xDimension * zDimension).
  constexpr std::uint64_t kMaxElevationGridPoints = std::uint64_t{1} << 22;
  const auto nx = static_cast<std::size_t>(xDim);
  std::size_t nz = static_cast<std::size_t>(zDim);
  const std::uint64_t wanted = static_cast<std::uint64_t>(xDim) * static_cast<std::uint64_t>(zDim);
  if (wanted > heights && wanted > kMaxElevationGridPoints) {
    log.add("height has " + std::to_string(heights) + " values but xDimension * " +
            "zDimension = " + std::to_string(static_cast<std::int64_t>(xDim) * zDim) +
            "; only complete rows are used");
    nz = heights / nx;
    if (nz < 2) return {};
  } else if (wanted > heights && heights > 0) {
    log.add("height has " + std::to_string(heights) + " values but xDimension * " +
            "zDimension = " + std::to_string(static_cast<std::int64_t>(xDim) * zDim) +
            "; the missing heights are 0");
  }

  std::vector<glm::vec3> points(nx * nz);
  if (geo) {
    // Columns go east (longitude, easting), rows north (latitude, northing), heights are
    // elevations times yScale; the standard order puts latitude or northing first.
    const geospatial::GeoSystem system = geoSystemOf(node);
    const geospatial::LocalFrame frame = geoFrameOf(node);
    const glm::dvec3 origin = node.get<FieldType::SFVec3d>("geoGridOrigin", glm::dvec3(0.0));
    const double yScale = node.get<FieldType::SFFloat>("yScale", 1.0f);
    for (std::size_t j = 0; j < nz; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const double east = static_cast<double>(i) * xSpacing;
        const double north = static_cast<double>(j) * zSpacing;
        const glm::dvec3 at = system.standardOrder ? origin + glm::dvec3(north, east, 0.0)
                                                   : origin + glm::dvec3(east, north, 0.0);
        const glm::dvec3 p = geospatial::toLocal(
            frame,
            geospatial::toGeocentric(system, {at.x, at.y, origin.z + height(i + j * nx) * yScale}));
        points[i + j * nx] = glm::vec3(p);
      }
  } else {
    for (std::size_t j = 0; j < nz; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        points[i + j * nx] = elevationGridPoint(xSpacing, zSpacing, i, j, height(i + j * nx));
  }

  PolygonSoup soup = polygonSoupOf(node, points);
  const ColorSource colors(node);  // Color or X3D ColorRGBA
  const auto& normals = childArray<FieldType::MFVec3f>(node, "normal", "vector");
  // A TextureCoordinate, an X3D TextureCoordinate3D / 4D (Mesh::texCoordsStrq), or a
  // MultiTextureCoordinate's first set and second (Mesh::texCoords1), as IndexedFaceSet
  // reads them; a TextureCoordinateGenerator is computed when drawn (the grid's own
  // coordinates stay for what reads none).
  TexSource texKind = TexSource::none;
  const StrqPoints strq = strqTexCoordPoints(node);
  const auto& texPoints = strq.present ? strq.st : texCoordPoints(node, texKind);
  if (strq.present) texKind = TexSource::points;
  const bool haveColor = colors.present();
  const bool haveNormal = node.sfnode("normal") != nullptr;
  const bool haveTex = texKind == TexSource::points;
  const std::vector<glm::vec2>* tex1 = haveTex ? secondTexCoordPoints(node) : nullptr;
  const bool colorPerVertex = node.get<FieldType::SFBool>("colorPerVertex", true);
  const bool normalPerVertex = node.get<FieldType::SFBool>("normalPerVertex", true);
  const std::size_t quads = (nx - 1) * (nz - 1);
  if (haveColor && colors.size() < (colorPerVertex ? nx * nz : quads))
    log.add("Color has " + std::to_string(colors.size()) + " colours, fewer than the grid needs");
  if (haveNormal && normals.size() < (normalPerVertex ? nx * nz : quads))
    log.add("Normal has " + std::to_string(normals.size()) + " vectors, fewer than the grid needs");
  if (haveTex && texPoints.size() < nx * nz)
    log.add("TextureCoordinate has " + std::to_string(texPoints.size()) +
            " points, fewer than the grid needs");

  soup.corners.reserve(4 * quads);
  soup.faceStart.reserve(quads + 1);
  const glm::vec3 kNoNormal(std::numeric_limits<float>::quiet_NaN());
  bool skipped = false;
  for (std::size_t j = 0; j + 1 < nz; ++j) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      // Counterclockwise seen from +Y: normals point up when ccw is TRUE (a geo grid's rows
      // go north, -Z in the up frame: its corners go the other way round).
      const std::size_t plainI[4] = {i, i, i + 1, i + 1}, plainJ[4] = {j, j + 1, j + 1, j};
      const std::size_t geoI[4] = {i, i + 1, i + 1, i}, geoJ[4] = {j, j, j + 1, j + 1};
      const std::size_t* ci = geo ? geoI : plainI;
      const std::size_t* cj = geo ? geoJ : plainJ;
      const auto id = [&](int c) { return static_cast<std::uint32_t>(ci[c] + cj[c] * nx); };
      // Two triangles across the diagonal from (i, j) to (i + 1, j + 1), as X_ITE splits
      // the cell: a cell whose four heights are not in one plane is two facets.
      if (!finite(points[id(0)]) || !finite(points[id(1)]) || !finite(points[id(2)]) ||
          !finite(points[id(3)])) {
        skipped = true;
        continue;
      }
      addFace(soup, {id(0), id(1), id(2)});
      addFace(soup, {id(0), id(2), id(3)});
      const std::size_t q = i + j * (nx - 1);
      for (int c : {0, 1, 2, 0, 2, 3}) {
        const std::size_t v = id(c);
        if (haveColor) {
          const std::size_t k = colorPerVertex ? v : q;
          soup.colors.push_back(k < colors.size() ? colors[k] : kWhite);
        }
        if (haveNormal) {
          const std::size_t k = normalPerVertex ? v : q;
          soup.normals.push_back(k < normals.size() ? normals[k] : kNoNormal);
        }
        if (haveTex) {
          addTexCorner(soup, texPoints, strq, tex1, v);
        } else {
          soup.texCoords.emplace_back(static_cast<float>(ci[c]) / static_cast<float>(nx - 1),
                                      static_cast<float>(cj[c]) / static_cast<float>(nz - 1));
        }
      }
    }
  }
  if (skipped) log.add("height has values that are not finite numbers; their quads are skipped");
  return buildPolygonMesh(soup);
}

// ---------------------------------------------------------------------------------------
// Extrusion

namespace {

bool isZero(const glm::dvec3& v) {
  return glm::dot(v, v) < 1e-24;
}

/// Rotation matrix of `angle` radians about `axis` (identity when the axis is zero).
glm::dmat3 rotation(glm::dvec3 axis, double angle) {
  const double len = glm::length(axis);
  if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(angle)) return glm::dmat3(1.0);
  axis /= len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  // Column-major: m[col][row].
  return glm::dmat3(t * x * x + c, t * x * y + s * z, t * x * z - s * y,  //
                    t * x * y - s * z, t * y * y + c, t * y * z + s * x,  //
                    t * x * z + s * y, t * y * z - s * x, t * z * z + c);
}

/// The rotation taking +Y onto the unit vector `y`, applied to +Z (clause 6.19: the SCP of
/// an entirely collinear spine). Turning +Y onto -Y is done about the X axis.
glm::dvec3 collinearZ(const glm::dvec3& y) {
  const glm::dvec3 axis = glm::cross(glm::dvec3(0, 1, 0), y);
  const double angle = std::acos(std::clamp(y.y, -1.0, 1.0));
  if (isZero(axis)) return y.y > 0.0 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 0, -1);
  return rotation(axis, angle) * glm::dvec3(0, 0, 1);
}

/// The spine-aligned cross-section planes (clause 6.19): per spine point the X, Y and Z
/// axes, each unit length and right-handed.
std::vector<glm::dmat3> spineFrames(const std::vector<glm::dvec3>& spine, bool closed) {
  const std::size_t n = spine.size();
  std::vector<glm::dvec3> ys(n), zs(n);
  std::vector<bool> zDefined(n, false);
  glm::dvec3 firstY(0, 1, 0);
  for (std::size_t i = 1; i < n; ++i) {
    if (!isZero(spine[i] - spine[i - 1])) {
      firstY = glm::normalize(spine[i] - spine[i - 1]);
      break;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    glm::dvec3 y, z(0.0);
    const bool end = (i == 0 || i == n - 1);
    if (end && closed) {
      y = spine[1] - spine[n - 2];
      z = glm::cross(spine[1] - spine[0], spine[n - 2] - spine[0]);
    } else if (i == 0) {
      y = spine[1] - spine[0];
    } else if (i == n - 1) {
      y = spine[n - 1] - spine[n - 2];
    } else {
      y = spine[i + 1] - spine[i - 1];
      z = glm::cross(spine[i + 1] - spine[i], spine[i - 1] - spine[i]);
    }
    ys[i] = !isZero(y) ? glm::normalize(y) : (i == 0 ? firstY : ys[i - 1]);
    zDefined[i] = !isZero(z);
    if (zDefined[i]) zs[i] = glm::normalize(z);
  }
  // Undefined Z: the first defined one before any, else the previous; none at all means
  // the whole spine is collinear.
  const auto first = std::find(zDefined.begin(), zDefined.end(), true);
  const glm::dvec3 z0 = first != zDefined.end()
                            ? zs[static_cast<std::size_t>(first - zDefined.begin())]
                            : collinearZ(firstY);
  std::vector<glm::dmat3> frames(n);
  glm::dvec3 prevZ = z0;
  for (std::size_t i = 0; i < n; ++i) {
    glm::dvec3 z = zDefined[i] ? zs[i] : prevZ;
    if (i > 0 && glm::dot(z, prevZ) < 0.0) z = -z;  // keep Z from flipping along the spine
    prevZ = z;
    const glm::dvec3 y = ys[i];
    glm::dvec3 zz = z - glm::dot(z, y) * y;  // make exactly perpendicular to Y
    if (isZero(zz))
      zz = glm::cross(std::abs(y.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), y);
    zz = glm::normalize(zz);
    frames[i] = glm::dmat3(glm::cross(y, zz), y, zz);
  }
  return frames;
}

/// Cumulative length along a polyline, normalized to [0, 1] (uniform when it has none).
template <class V>
std::vector<float> arcLength(std::span<const V> p, std::size_t n) {
  std::vector<double> d(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    using D = glm::vec<V::length(), double>;
    d[i] = d[i - 1] + glm::length(D(p[i]) - D(p[i - 1]));
  }
  std::vector<float> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = d[n - 1] > 0.0 ? static_cast<float>(d[i] / d[n - 1])
                            : static_cast<float>(i) / static_cast<float>(n - 1);
  return out;
}

}  // namespace

Mesh tessellateExtrusion(const Node& node, ProblemLog& log) {
  // The clause 6.19 defaults, for nodes whose type lacks a field (the node table has them).
  static const std::vector<glm::vec3> kSpine = {{0, 0, 0}, {0, 1, 0}};
  static const std::vector<glm::vec2> kSquare = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {1, 1}};
  static const std::vector<glm::vec2> kScale = {{1, 1}};
  static const std::vector<Rotation> kOrientation = {{0, 0, 1, 0}};
  ExtrusionInput in;
  in.spine = fieldOr<FieldType::MFVec3f>(node, "spine", kSpine);
  in.crossSection = fieldOr<FieldType::MFVec2f>(node, "crossSection", kSquare);
  in.scale = fieldOr<FieldType::MFVec2f>(node, "scale", kScale);
  in.orientation = fieldOr<FieldType::MFRotation>(node, "orientation", kOrientation);
  in.beginCap = node.get<FieldType::SFBool>("beginCap", true);
  in.endCap = node.get<FieldType::SFBool>("endCap", true);
  return extrude(
      in, [&](std::span<const glm::vec3> points) { return polygonSoupOf(node, points); }, log);
}

Mesh extrude(const ExtrusionInput& in,
             const std::function<PolygonSoup(std::span<const glm::vec3>)>& soupOf,
             ProblemLog& log) {
  const std::span<const glm::vec3> spineIn = in.spine;
  const std::span<const glm::vec2> cs = in.crossSection;
  const std::span<const glm::vec2> scale = in.scale;
  const std::span<const Rotation> orientation = in.orientation;
  std::size_t ns = spineIn.size();
  const std::size_t nc = cs.size();
  if (ns < 2 || nc < 2) return {};
  for (const glm::vec3& p : spineIn)
    if (!finite(p)) return log.add("spine has a value that is not a finite number"), Mesh{};
  for (const glm::vec2& p : cs)
    if (!finite(p)) return log.add("crossSection has a value that is not a finite number"), Mesh{};
  if (ns * nc > kMaxExtrusionPoints) {
    log.add(std::to_string(ns) + " spine x " + std::to_string(nc) +
            " crossSection points is more than the limit of " +
            std::to_string(kMaxExtrusionPoints) +
            " (vrml::kMaxExtrusionPoints); the spine is cut short");
    ns = kMaxExtrusionPoints / nc;
    if (ns < 2) return {};
  }
  if (scale.size() != 1 && scale.size() < ns)
    log.add("scale has " + std::to_string(scale.size()) + " values for " + std::to_string(ns) +
            " spine points; the first is used throughout");
  if (orientation.size() != 1 && orientation.size() < ns)
    log.add("orientation has " + std::to_string(orientation.size()) + " values for " +
            std::to_string(ns) + " spine points; the first is used throughout");

  std::vector<glm::dvec3> spine(spineIn.begin(), spineIn.begin() + static_cast<std::ptrdiff_t>(ns));
  const bool spineClosed = ns > 2 && spine.front() == spine.back();
  const bool csClosed = nc > 2 && cs.front() == cs.back();
  const std::vector<glm::dmat3> frames = spineFrames(spine, spineClosed);

  // Grid points: ring i (spine point), column j (cross-section point). A closed
  // cross-section's last column is its first; a closed spine's last ring is its first
  // when the two rings coincide. Shared points let creaseAngle smooth across the seams.
  const std::size_t cols = csClosed ? nc - 1 : nc;
  std::vector<glm::vec3> ring(cols);
  std::vector<glm::vec3> points;
  points.reserve(ns * cols);
  for (std::size_t i = 0; i < ns; ++i) {
    const glm::vec2 sc = scale.size() >= ns ? scale[i] : (scale.empty() ? glm::vec2(1) : scale[0]);
    const Rotation r = orientation.size() >= ns
                           ? orientation[i]
                           : (orientation.empty() ? Rotation(0, 0, 1, 0) : orientation[0]);
    const glm::dmat3 m = frames[i] * rotation(glm::dvec3(r), double{r.w});
    for (std::size_t j = 0; j < cols; ++j) {
      const glm::dvec3 local(double{sc.x} * cs[j].x, 0.0, double{sc.y} * cs[j].y);
      ring[j] = glm::vec3(spine[i] + m * local);
    }
    if (i == ns - 1 && spineClosed && std::equal(ring.begin(), ring.end(), points.begin())) break;
    points.insert(points.end(), ring.begin(), ring.end());
  }
  const std::size_t rings = points.size() / cols;
  auto id = [&](std::size_t i, std::size_t j) {
    return static_cast<std::uint32_t>((i % rings) * cols + (j % cols));
  };
  // The caps get points of their own: their normals are the caps' flat ones, never
  // smoothed with the sides whatever the creaseAngle (as X_ITE builds them: it refines the
  // body's normals only).
  const bool caps = cols >= 3 && (in.beginCap || in.endCap);
  const auto capBase = [&](std::size_t capRing) {
    const auto base = static_cast<std::uint32_t>(points.size());
    for (std::size_t j = 0; j < cols; ++j) {
      const glm::vec3 p = points[id(capRing, j)];
      points.push_back(p);
    }
    return base;
  };
  const std::uint32_t beginBase = caps && in.beginCap ? capBase(0) : 0;
  const std::uint32_t endBase = caps && in.endCap ? capBase(ns - 1) : 0;

  PolygonSoup soup = soupOf(points);
  const std::vector<float> s = arcLength<glm::vec2>(cs, nc), t = arcLength<glm::dvec3>(spine, ns);
  bool skipped = false;
  soup.corners.reserve(4 * (ns - 1) * (nc - 1) + 2 * cols);
  // Sides: with the crossSection counterclockwise seen from +Y (as the default square
  // is) and ccw TRUE, the quads face outwards.
  for (std::size_t i = 0; i + 1 < ns; ++i) {
    for (std::size_t j = 0; j + 1 < nc; ++j) {
      if (!addFace(soup, {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)})) {
        skipped = true;
        continue;
      }
      soup.texCoords.insert(
          soup.texCoords.end(),
          {{s[j], t[i]}, {s[j + 1], t[i]}, {s[j + 1], t[i + 1]}, {s[j], t[i + 1]}});
    }
  }
  // Caps: the crossSection polygon at the first ring (reversed, facing backwards) and
  // at the last ring. Texture: the crossSection's bounding box scaled uniformly so that
  // its larger side spans 0..1, S along X and T along Z.
  glm::vec2 lo = cs[0], hi = cs[0];
  for (std::size_t j = 0; j < cols; ++j) lo = glm::min(lo, cs[j]), hi = glm::max(hi, cs[j]);
  const float big = std::max(hi.x - lo.x, hi.y - lo.y);
  auto cap = [&](std::uint32_t base, bool reversed) {
    std::vector<std::uint32_t> ids(cols);
    for (std::size_t k = 0; k < cols; ++k)
      ids[k] = base + static_cast<std::uint32_t>(reversed ? cols - 1 - k : k);
    for (std::uint32_t p : ids)
      if (!finite(points[p])) return void(skipped = true);
    soup.corners.insert(soup.corners.end(), ids.begin(), ids.end());
    soup.endFace();
    for (std::size_t k = 0; k < cols; ++k) {
      const glm::vec2 c = cs[reversed ? cols - 1 - k : k];
      soup.texCoords.push_back(big > 0.0f ? (c - lo) / big : glm::vec2(0.0f));
    }
  };
  if (caps) {
    if (in.beginCap) cap(beginBase, true);
    if (in.endCap) cap(endBase, false);
  }
  if (skipped) log.add("spine, scale or orientation give points that are not finite numbers");
  return buildPolygonMesh(soup);
}

}  // namespace gs::vrml::geometry_detail
