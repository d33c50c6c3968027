// View requests on a view-dependent splat set (render/splat_renderer.hpp): a renderer
// registers one, updates it as it draws and releases it when it goes.
#include "render/splat_renderer.hpp"

#include <catch2/catch.hpp>

using gs::render::SplatSet;
using gs::render::SplatView;

TEST_CASE("splat view requests: registered, updated and released", "[splat][tileset]") {
  auto set = std::make_shared<SplatSet>();
  auto a = set->viewRequests->request();
  auto b = set->viewRequests->request();
  CHECK(set->viewRequests->views().empty());  // no view until drawn
  SplatView v;
  v.vectors = 10;
  a->update(v);
  v.vectors = 20;
  b->update(v);
  REQUIRE(set->viewRequests->views().size() == 2);
  CHECK(set->viewRequests->views().begin()->second.vectors == 10);  // in request order
  v.vectors = 15;
  a->update(v);
  CHECK(set->viewRequests->views().size() == 2);
  CHECK(set->viewRequests->views().begin()->second.vectors == 15);
  a.reset();  // a viewport closed
  REQUIRE(set->viewRequests->views().size() == 1);
  CHECK(set->viewRequests->views().begin()->second.vectors == 20);
  // A request that outlives its set is released quietly.
  set.reset();
  b->update(v);
  b.reset();
}
