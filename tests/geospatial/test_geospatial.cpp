// X3D Geospatial (X3D 4.0 clause 25): the spatial reference frames and their conversions
// (geospatial/geo_system.hpp, GeographicLib), the local frame of a GeoOrigin, and the geo
// nodes as geometry and grouping read them (vrml/geo_nodes.hpp, geometry, vrml/transform).
#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"
#include "geospatial/geo_system.hpp"
#include "scene/traversal.hpp"
#include "vrml/geo_nodes.hpp"
#include "vrml/transform.hpp"

#include <catch2/catch.hpp>

#include <functional>

using namespace gs;

namespace {

constexpr double kA = 6378137.0;          // WGS84 semi-major axis
constexpr double kB = 6356752.314245179;  // and semi-minor

void requireNear(const glm::dvec3& a, const glm::dvec3& b, double margin) {
  INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z
           << ")");
  REQUIRE(glm::length(a - b) <= margin);
}

const vrml::Node& named(const vrml::Scene& scene, const std::string& name) {
  const vrml::Node* found = nullptr;
  std::function<void(const vrml::NodePtr&)> visit = [&](const vrml::NodePtr& n) {
    if (!n || found) return;
    if (n->defName == name) found = n.get();
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() == vrml::FieldType::SFNode) visit(v.get<vrml::FieldType::SFNode>());
      if (v.type() == vrml::FieldType::MFNode)
        for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>()) visit(c);
    }
  };
  for (const vrml::NodePtr& n : scene.rootNodes) visit(n);
  REQUIRE(found != nullptr);
  return *found;
}

}  // namespace

TEST_CASE("geospatial: GD, UTM and GC frames convert to geocentric and back", "[geospatial]") {
  using geospatial::parseGeoSystem;
  const auto gd = parseGeoSystem({"GD", "WE"});
  requireNear(geospatial::toGeocentric(gd, {0, 0, 0}), {kA, 0, 0}, 1e-6);
  requireNear(geospatial::toGeocentric(gd, {90, 0, 0}), {0, 0, kB}, 1e-6);
  requireNear(geospatial::toGeocentric(gd, {0, 90, 100}), {0, kA + 100, 0}, 1e-6);
  // longitude_first swaps the first two numbers.
  const auto lonFirst = parseGeoSystem({"GD", "WE", "longitude_first"});
  requireNear(geospatial::toGeocentric(lonFirst, {90, 0, 100}), {0, kA + 100, 0}, 1e-6);
  // Round trips.
  const glm::dvec3 somewhere{35.25, -120.5, 1234.0};
  requireNear(geospatial::fromGeocentric(gd, geospatial::toGeocentric(gd, somewhere)), somewhere,
              1e-6);
  // UTM zone 10 north: its central meridian -123 degrees at easting 500 km; northing first.
  const auto utm = parseGeoSystem({"UTM", "Z10"});
  CHECK(utm.kind == geospatial::GeoSystem::Kind::utm);
  CHECK(utm.zone == 10);
  requireNear(geospatial::toGeocentric(utm, {0, 500000, 0}),
              geospatial::toGeocentric(gd, {0, -123, 0}), 1e-3);
  const glm::dvec3 utmPoint{4000000.0, 600000.0, 50.0};
  requireNear(geospatial::fromGeocentric(utm, geospatial::toGeocentric(utm, utmPoint)), utmPoint,
              1e-3);
  const auto easting = parseGeoSystem({"UTM", "Z10", "easting_first"});
  requireNear(geospatial::toGeocentric(easting, {600000.0, 4000000.0, 50.0}),
              geospatial::toGeocentric(utm, utmPoint), 1e-6);
  // GC is itself; another ellipsoid moves the points.
  const auto gc = parseGeoSystem({"GC"});
  requireNear(geospatial::toGeocentric(gc, {1, 2, 3}), {1, 2, 3}, 0.0);
  const auto clarke = parseGeoSystem({"GD", "CC"});
  CHECK(geospatial::toGeocentric(clarke, {0, 0, 0}).x == Approx(6378206.4));
  std::string problem;
  parseGeoSystem({"GD", "XX"}, &problem);
  CHECK(problem.find("'XX'") != std::string::npos);
}

TEST_CASE("geospatial: a GeoOrigin's local frame, rotateYUp and location matrices",
          "[geospatial]") {
  const auto gd = geospatial::parseGeoSystem({"GD", "WE"});
  const glm::dvec3 origin{45, -80, 0};
  const auto plain = geospatial::originFrame(gd, origin, false);
  const auto up = geospatial::originFrame(gd, origin, true);
  const glm::dvec3 at = geospatial::toGeocentric(gd, origin);
  requireNear(geospatial::toLocal(plain, at), {0, 0, 0}, 1e-6);
  requireNear(geospatial::toLocal(up, at), {0, 0, 0}, 1e-6);
  // 1000 m above the origin is +Y with rotateYUp; a point to the north is -Z (Z is south).
  requireNear(geospatial::toLocal(up, geospatial::toGeocentric(gd, {45, -80, 1000})), {0, 1000, 0},
              1e-3);
  const glm::dvec3 north = geospatial::toLocal(up, geospatial::toGeocentric(gd, {45.01, -80, 0}));
  CHECK(north.z < -1000.0);
  CHECK(std::abs(north.x) < 1.0);
  const glm::dvec3 east = geospatial::toLocal(up, geospatial::toGeocentric(gd, {45, -79.99, 0}));
  CHECK(east.x > 700.0);
  // A GeoLocation at the origin of a rotateYUp frame is the identity there.
  const glm::dmat4 m = geospatial::locationMatrix(up, gd, origin);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK(m[c][r] == Approx(c == r ? 1.0 : 0.0).margin(1e-9));
  requireNear(geospatial::fromLocal(up, {0, 1000, 0}),
              geospatial::toGeocentric(gd, {45, -80, 1000}), 1e-3);
}

TEST_CASE(
    "geospatial: GeoCoordinate, GeoElevationGrid, GeoLocation and GeoTransform place "
    "geometry in the GeoOrigin's frame",
    "[geospatial]") {
  const vrml::Scene scene = vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
DEF LOC GeoLocation {
  geoOrigin DEF O GeoOrigin { geoCoords 45 -80 0 rotateYUp TRUE }
  geoCoords 45 -80 100
}
Shape { geometry DEF FACES IndexedFaceSet {
  coord GeoCoordinate { geoOrigin USE O point [ 45 -80 0, 45 -79.99 0, 45.01 -80 0 ] }
  coordIndex [ 0 1 2 -1 ]
} }
Shape { geometry DEF GRID GeoElevationGrid {
  geoOrigin USE O geoGridOrigin 45 -80 0 xDimension 2 zDimension 2
  xSpacing 0.01 zSpacing 0.01 height [ 0 0 0 0 ]
} }
DEF GT GeoTransform { geoOrigin USE O geoCenter 45 -80 0 translation 0 10 0 }
)",
                                            "geo.x3dv");
  REQUIRE(scene.diagnostics.items.empty());
  const glm::mat4 loc = vrml::transformMatrix(named(scene, "LOC"));
  CHECK(loc[3].y == Approx(100.0f).margin(1e-2));
  CHECK(loc[1].y == Approx(1.0f).margin(1e-6));
  const vrml::Mesh faces = vrml::tessellate(named(scene, "FACES"));
  REQUIRE(faces.positions.size() == 3);
  CHECK(glm::length(faces.positions[0]) < 1e-2f);
  CHECK(faces.positions[1].x > 700.0f);    // east
  CHECK(faces.positions[2].z < -1000.0f);  // north
  const vrml::Mesh grid = vrml::tessellate(named(scene, "GRID"));
  REQUIRE(grid.triangleCount() == 2);
  // Facing up from the ground, as an ElevationGrid does.
  for (const glm::vec3& n : grid.normals) CHECK(n.y > 0.99f);
  CHECK(grid.bounds.max.x > 700.0f);
  CHECK(grid.bounds.min.z < -1000.0f);
  const glm::mat4 gt = vrml::transformMatrix(named(scene, "GT"));
  CHECK(gt[3].y == Approx(10.0f).margin(1e-3));  // up the local up at geoCenter
}

TEST_CASE("geospatial: a GeoViewpoint's camera is at its geo position, turned in the up frame",
          "[geospatial]") {
  auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
GeoViewpoint {
  geoOrigin GeoOrigin { geoCoords 45 -80 0 rotateYUp TRUE }
  position 45 -80 1000 orientation 1 0 0 -1.5707963
}
)",
                                                             "gv.x3dv"));
  scene::SceneTraversal traversal(scene);
  REQUIRE(traversal.viewpoints().size() == 1);
  const scene::Camera& c = traversal.viewpoints()[0].camera;
  CHECK(c.position.y == Approx(1000.0f).margin(1e-2));
  CHECK(std::abs(c.position.x) < 1e-2f);
  // Turned -90 degrees about X: looking straight down.
  CHECK(c.forward().y == Approx(-1.0f).margin(1e-4));
}

TEST_CASE("geospatial: a bound GeoViewpoint scales the navigation speed by its elevation",
          "[geospatial]") {
  // X_ITE 15's rule: (max(elevation, 0) + 10) / 10 times speedFactor.
  auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
NavigationInfo { speed 3 }
DEF High GeoViewpoint { position 45 -80 990 speedFactor 2 }
DEF Orbit GeoViewpoint { geoSystem "GC" position 6378227 0 0 }
DEF Under GeoViewpoint { position 10 20 -500 }
DEF Plain Viewpoint { }
)",
                                                             "speed.x3dv"));
  CHECK(scene::viewpointSpeedFactor(named(*scene, "High")) == Approx(200.0f).epsilon(1e-5));
  CHECK(scene::viewpointSpeedFactor(named(*scene, "Orbit")) == Approx(10.0f).epsilon(1e-5));
  CHECK(scene::viewpointSpeedFactor(named(*scene, "Under")) == Approx(1.0f));
  CHECK(scene::viewpointSpeedFactor(named(*scene, "Plain")) == 1.0f);
  // The first Viewpoint is bound: the world's navigation gets its factor.
  scene::SceneTraversal traversal(scene);
  CHECK(traversal.navigation().speed == 3.0f);
  CHECK(traversal.navigation().speedFactor == Approx(200.0f).epsilon(1e-5));
}

TEST_CASE("geospatial: a geoSystem word not understood is a warning at the geometry",
          "[geospatial]") {
  const vrml::Scene scene = vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
Shape { geometry DEF G GeoElevationGrid { geoSystem [ "GD" "XX" ] xDimension 2 zDimension 2
  height [ 0 0 0 0 ] } }
)",
                                            "bad.x3dv");
  vrml::Diagnostics diag;
  const vrml::Mesh mesh = vrml::tessellate(named(scene, "G"), &diag);
  CHECK(mesh.triangleCount() == 2);  // still drawn, in GD WE
  REQUIRE(diag.items.size() == 1);
  CHECK(diag.items[0].message.find("'XX'") != std::string::npos);
}

TEST_CASE("geospatial: a GeoElevationGrid's creaseAngle (an SFDouble) smooths its normals",
          "[geospatial]") {
  // A ridge along the grid's middle column: faceted, the two slopes' corners at the ridge
  // keep their own slopes' normals; at creaseAngle 3.14 they share one, straight up.
  const auto ridge = [](const char* crease) {
    return std::string(R"(#X3D V4.0 utf8
PROFILE Full
Shape { geometry DEF G GeoElevationGrid {
  geoOrigin GeoOrigin { geoCoords 45 -80 0 rotateYUp TRUE }
  geoGridOrigin 45 -80 0 xDimension 3 zDimension 2 xSpacing 0.01 zSpacing 0.01
  height [ 0 500 0, 0 500 0 ] )") +
           crease + " } }\n";
  };
  const auto ridgeNormals = [](const vrml::Mesh& mesh) {
    std::vector<glm::vec3> out;
    const float top = mesh.bounds.max.y;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      if (mesh.positions[i].y > top - 1.0f) out.push_back(mesh.normals[i]);
    return out;
  };
  const vrml::Scene faceted = vrml::parseVrml(ridge(""), "faceted.x3dv");
  const vrml::Scene smooth = vrml::parseVrml(ridge("creaseAngle 3.14"), "smooth.x3dv");
  REQUIRE(faceted.diagnostics.items.empty());
  REQUIRE(smooth.diagnostics.items.empty());
  const auto sharp = ridgeNormals(vrml::tessellate(named(faceted, "G")));
  const auto round = ridgeNormals(vrml::tessellate(named(smooth, "G")));
  REQUIRE(sharp.size() >= 4);
  REQUIRE(round.size() >= 2);  // smooth corners share their points
  for (const glm::vec3& n : sharp) CHECK(std::abs(n.x) > 0.3f);  // a slope's normal
  for (const glm::vec3& n : round) {
    CHECK(std::abs(n.x) < 0.05f);  // the ridge's: up
    CHECK(n.y > 0.99f);
  }
}
