// Geospatial coordinates (ISO/IEC 19775-1:2023, X3D 4.0 clause 25 "Geospatial"): the
// spatial reference frames of a node's `geoSystem` (GD geodetic, UTM, GC geocentric, with
// an ellipsoid of table 25.3), their conversion to and from geocentric coordinates through
// GeographicLib, and the local frame of the world: coordinates relative to a GeoOrigin,
// optionally turned so that +Y is up there (`rotateYUp`), as X_ITE 15 places them. Pure
// math in double precision; metres and degrees (GD), metres (UTM, GC).
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gs::geospatial {

/// A spatial reference frame (clause 25.2.2).
struct GeoSystem {
  enum class Kind { geodetic, utm, geocentric };
  Kind kind = Kind::geodetic;
  double a = 6378137.0;            // ellipsoid semi-major axis, metres (WGS84: "WE")
  double f = 1.0 / 298.257223563;  // flattening
  int zone = 0;                    // UTM zone 1..60
  bool north = true;               // UTM hemisphere
  /// Coordinates in the standard order: GD latitude, longitude, elevation
  /// ("latitude_first", the default; "longitude_first" swaps); UTM northing, easting,
  /// elevation (the default; "easting_first" swaps).
  bool standardOrder = true;
};

/// The frame a `geoSystem` MFString names: "GD" / "GDC" with an optional ellipsoid code
/// (table 25.3: AA, AM, AN, BN, BR, CC, CD, EA ... WD, WE; default WE) and "longitude_first";
/// "UTM" with "Zn" (1..60), "S" for the southern hemisphere, "easting_first", an ellipsoid;
/// "GC" / "GCC". Empty: GD WE. A word it does not know is put in `problem` (when not null)
/// and left out; an unknown frame reads as GD.
GeoSystem parseGeoSystem(const std::vector<std::string>& spec, std::string* problem = nullptr);

/// Geocentric (earth-centred, earth-fixed) metres of `coords` in `system`: GD (degrees,
/// degrees, metres above the ellipsoid), UTM (metres), GC (itself).
glm::dvec3 toGeocentric(const GeoSystem& system, const glm::dvec3& coords);
/// The inverse of toGeocentric (GD: latitude in [-90, 90], longitude in (-180, 180]).
glm::dvec3 fromGeocentric(const GeoSystem& system, const glm::dvec3& geocentric);

/// The up direction (unit ellipsoid normal) at geocentric point `p` for the ellipsoid of
/// `system`; +Z at the centre.
glm::dvec3 upVector(const GeoSystem& system, const glm::dvec3& p);

/// X_ITE's standard location frame at geocentric point `p` (column-major, glm): columns X =
/// normalize(+Z x up) (east; +X at the poles), Y = up, Z = X x Y (south), origin p.
glm::dmat4 standardLocationMatrix(const GeoSystem& system, const glm::dvec3& p);

/// The world's local frame (a GeoOrigin, X3D 4.0 clause 25.4.8): local coordinates are
/// geocentric ones minus the origin, or with rotateYUp expressed in the standard location
/// frame at the origin (so +Y is up there). Without a GeoOrigin, geocentric coordinates.
struct LocalFrame {
  bool hasOrigin = false;
  bool rotateYUp = false;
  glm::dvec3 origin{0.0};         // geocentric metres
  glm::dmat4 originMatrix{1.0};   // standardLocationMatrix at the origin
  glm::dmat4 inverseOrigin{1.0};  // its inverse
};

/// The frame of a GeoOrigin with `geoSystem`, `geoCoords` and `rotateYUp`.
LocalFrame originFrame(const GeoSystem& system, const glm::dvec3& geoCoords, bool rotateYUp);

/// Local coordinates (metres) of geocentric point `p`.
glm::dvec3 toLocal(const LocalFrame& frame, const glm::dvec3& p);
/// Geocentric point of local coordinates `p`.
glm::dvec3 fromLocal(const LocalFrame& frame, const glm::dvec3& p);

/// The matrix placing a GeoLocation's children (clause 25.4.5) at `geoCoords` of `system`
/// in local coordinates: +Y up (the ellipsoid normal), +X east, +Z south there.
glm::dmat4 locationMatrix(const LocalFrame& frame, const GeoSystem& system,
                          const glm::dvec3& geoCoords);

}  // namespace gs::geospatial
