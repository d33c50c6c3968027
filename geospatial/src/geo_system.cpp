#include "geospatial/geo_system.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string_view>

namespace gs::geospatial {

namespace {

struct Ellipsoid {
  std::string_view code;
  double a;
  double inverseFlattening;
};

// X3D 4.0 clause 25.2.3, table 25.3 "Supported earth ellipsoids".
constexpr Ellipsoid kEllipsoids[] = {
    {"AA", 6377563.396, 299.3249646}, {"AM", 6377340.189, 299.3249646},
    {"AN", 6378160.0, 298.25},        {"BN", 6377483.865, 299.1528128},
    {"BR", 6377397.155, 299.1528128}, {"CC", 6378206.4, 294.9786982},
    {"CD", 6378249.145, 293.465},     {"EA", 6377276.345, 300.8017},
    {"EB", 6377298.556, 300.8017},    {"EC", 6377301.243, 300.8017},
    {"ED", 6377304.063, 300.8017},    {"EE", 6377295.664, 300.8017},
    {"EF", 6377309.613, 300.8017},    {"FA", 6378155.0, 298.3},
    {"HE", 6378200.0, 298.3},         {"HO", 6378270.0, 297.0},
    {"ID", 6378160.0, 298.247},       {"IN", 6378388.0, 297.0},
    {"KA", 6378245.0, 298.3},         {"RF", 6378137.0, 298.257222101},
    {"SA", 6378160.0, 298.25},        {"WD", 6378135.0, 298.26},
    {"WE", 6378137.0, 298.257223563},
};

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

GeographicLib::Geocentric earth(const GeoSystem& s) {
  try {
    return GeographicLib::Geocentric(s.a, s.f);
  } catch (const std::exception&) {
    return GeographicLib::Geocentric::WGS84();
  }
}

}  // namespace

GeoSystem parseGeoSystem(const std::vector<std::string>& spec, std::string* problem) {
  GeoSystem s;
  const auto complain = [&](const std::string& word) {
    if (problem != nullptr && problem->empty())
      *problem = "geoSystem: '" + word + "' is no spatial reference frame word (X3D clause 25.2.2)";
  };
  bool first = true;
  for (const std::string& word : spec) {
    if (first) {
      first = false;
      if (word == "GD" || word == "GDC") {
        s.kind = GeoSystem::Kind::geodetic;
        continue;
      }
      if (word == "UTM") {
        s.kind = GeoSystem::Kind::utm;
        continue;
      }
      if (word == "GC" || word == "GCC") {
        s.kind = GeoSystem::Kind::geocentric;
        continue;
      }
      complain(word);
      continue;
    }
    if (word == "longitude_first" || word == "easting_first") {
      s.standardOrder = false;
      continue;
    }
    if (word == "latitude_first" || word == "northing_first" || word == "N") continue;
    if (word == "S") {
      s.north = false;
      continue;
    }
    if (word.size() >= 2 && word[0] == 'Z' && s.kind == GeoSystem::Kind::utm) {
      const int zone = std::atoi(word.c_str() + 1);
      if (zone >= 1 && zone <= 60) {
        s.zone = zone;
        continue;
      }
    }
    bool known = false;
    for (const Ellipsoid& e : kEllipsoids)
      if (word == e.code) {
        s.a = e.a;
        s.f = 1.0 / e.inverseFlattening;
        known = true;
      }
    if (!known) complain(word);
  }
  if (s.kind == GeoSystem::Kind::utm && s.zone == 0) s.zone = 1;
  return s;
}

glm::dvec3 toGeocentric(const GeoSystem& system, const glm::dvec3& coords) {
  if (!finite(coords)) return glm::dvec3(0.0);
  if (system.kind == GeoSystem::Kind::geocentric) return coords;
  double lat = 0.0, lon = 0.0;
  const double h = coords.z;
  if (system.kind == GeoSystem::Kind::geodetic) {
    lat = system.standardOrder ? coords.x : coords.y;
    lon = system.standardOrder ? coords.y : coords.x;
  } else {
    const double northing = system.standardOrder ? coords.x : coords.y;
    const double easting = system.standardOrder ? coords.y : coords.x;
    // The zone's transverse Mercator projection itself (UTMUPS would refuse eastings
    // outside the zone's band, which X3D worlds use: X_ITE converts them).
    const double lon0 = 6.0 * system.zone - 183.0;
    GeographicLib::TransverseMercator::UTM().Reverse(
        lon0, easting - 500000.0, system.north ? northing : northing - 10000000.0, lat, lon);
  }
  glm::dvec3 out(0.0);
  earth(system).Forward(std::clamp(lat, -90.0, 90.0), lon, h, out.x, out.y, out.z);
  return out;
}

glm::dvec3 fromGeocentric(const GeoSystem& system, const glm::dvec3& p) {
  if (system.kind == GeoSystem::Kind::geocentric || !finite(p)) return p;
  double lat = 0.0, lon = 0.0, h = 0.0;
  earth(system).Reverse(p.x, p.y, p.z, lat, lon, h);
  if (system.kind == GeoSystem::Kind::geodetic)
    return system.standardOrder ? glm::dvec3(lat, lon, h) : glm::dvec3(lon, lat, h);
  double x = 0.0, y = 0.0;
  GeographicLib::TransverseMercator::UTM().Forward(6.0 * system.zone - 183.0, lat, lon, x, y);
  const double easting = x + 500000.0;
  const double northing = system.north ? y : y + 10000000.0;
  return system.standardOrder ? glm::dvec3(northing, easting, h) : glm::dvec3(easting, northing, h);
}

glm::dvec3 upVector(const GeoSystem& system, const glm::dvec3& p) {
  if (!finite(p) || glm::length(p) == 0.0) return {0.0, 0.0, 1.0};
  double lat = 0.0, lon = 0.0, h = 0.0;
  earth(system).Reverse(p.x, p.y, p.z, lat, lon, h);
  const double phi = glm::radians(lat), lambda = glm::radians(lon);
  return {std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi)};
}

glm::dmat4 standardLocationMatrix(const GeoSystem& system, const glm::dvec3& p) {
  const glm::dvec3 y = upVector(system, p);
  glm::dvec3 x = glm::cross(glm::dvec3(0.0, 0.0, 1.0), y);
  if (glm::length(x) < 1e-12) x = glm::dvec3(1.0, 0.0, 0.0);  // at a pole
  x = glm::normalize(x);
  const glm::dvec3 z = glm::normalize(glm::cross(x, y));
  return glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(y, 0.0), glm::dvec4(z, 0.0), glm::dvec4(p, 1.0));
}

LocalFrame originFrame(const GeoSystem& system, const glm::dvec3& geoCoords, bool rotateYUp) {
  LocalFrame f;
  f.hasOrigin = true;
  f.rotateYUp = rotateYUp;
  f.origin = toGeocentric(system, geoCoords);
  f.originMatrix = standardLocationMatrix(system, f.origin);
  f.inverseOrigin = glm::inverse(f.originMatrix);
  return f;
}

glm::dvec3 toLocal(const LocalFrame& frame, const glm::dvec3& p) {
  if (frame.rotateYUp) return glm::dvec3(frame.inverseOrigin * glm::dvec4(p, 1.0));
  return p - frame.origin;
}

glm::dvec3 fromLocal(const LocalFrame& frame, const glm::dvec3& p) {
  if (frame.rotateYUp) return glm::dvec3(frame.originMatrix * glm::dvec4(p, 1.0));
  return p + frame.origin;
}

glm::dmat4 locationMatrix(const LocalFrame& frame, const GeoSystem& system,
                          const glm::dvec3& geoCoords) {
  glm::dmat4 m = standardLocationMatrix(system, toGeocentric(system, geoCoords));
  if (frame.rotateYUp) return frame.inverseOrigin * m;
  m[3] -= glm::dvec4(frame.origin, 0.0);
  return m;
}

}  // namespace gs::geospatial
