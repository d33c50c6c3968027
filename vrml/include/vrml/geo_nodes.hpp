// The Geospatial component's fields read from nodes (ISO/IEC 19775-1:2023, X3D 4.0 clause
// 25): a node's `geoSystem` and the local frame of its `geoOrigin` (geospatial/geo_system.hpp
// does the geodesy), so that geometry, grouping, viewpoints and interpolators place geo
// coordinates alike. Metres; double precision until the local coordinates are made.
#pragma once

#include "geospatial/geo_system.hpp"
#include "vrml/node.hpp"

#include <string>

namespace gs::vrml {

/// The frame `node`'s `geoSystem` field names (GD WE when it has none); a word that is not
/// understood goes to `problem` (when not null).
geospatial::GeoSystem geoSystemOf(const Node& node, std::string* problem = nullptr);

/// The local frame of `node`'s `geoOrigin` (a GeoOrigin: its geoSystem, geoCoords and
/// rotateYUp); geocentric coordinates when it has none.
geospatial::LocalFrame geoFrameOf(const Node& node);

/// Local coordinates (metres) of `geoCoords`, in `node`'s geoSystem and geoOrigin.
glm::dvec3 geoToLocal(const Node& node, const glm::dvec3& geoCoords);

/// The matrix placing children at `geoCoords` of `node`'s geoSystem, in its geoOrigin's
/// frame: +Y up, +X east, +Z south there (X3D 4.0 clause 25.4.5, as X_ITE places them).
glm::dmat4 geoLocationMatrix(const Node& node, const glm::dvec3& geoCoords);

}  // namespace gs::vrml
