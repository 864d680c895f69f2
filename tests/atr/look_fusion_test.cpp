// Multi-look fusion (atr/look_fusion.h): association by distance, the fused decision, counts.
#include "atr/look_fusion.h"

#include <catch2/catch.hpp>
#include <stdexcept>
#include <vector>

#include "tests/atr/classification_looks.h"

namespace sonarloop::atr {
namespace {

Model model3() {
  Model m;
  m.chip_width = 2;
  m.chip_height = 2;
  for (const char* n : {"a", "b", "c"}) {
    ClassModel c;
    c.name = n;
    c.typical_distance = 10.0f;
    m.classes.push_back(c);
  }
  return m;
}

using testing::look;

TEST_CASE("look fusion: looks within the radius join one object; the fused decision") {
  const Model m = model3();
  LookFusion f(2.0);
  // first look: b by a hair
  const FusedObject& o1 = f.add(1, 10.0, 20.0, m, look({10.2f, 10.0f, 14.0f}));
  CHECK(o1.looks == 1);
  CHECK(o1.id == 1);
  CHECK(o1.class_index == 1);
  // a look 1.5 m away, from another aspect: a clearly
  const FusedObject& o2 = f.add(2, 11.0, 21.1, m, look({8.0f, 11.0f, 14.0f}));
  CHECK(o2.looks == 2);
  CHECK(o2.id == 1);  // the first look's contact
  CHECK(o2.class_index == 0);
  CHECK(o2.fused[0] == Approx((10.2 + 8.0) / 10.0));
  CHECK(o2.north_m == Approx(10.5));
  CHECK(o2.east_m == Approx(20.55));
  // a look 5 m away is another object
  const FusedObject& o3 = f.add(3, 15.0, 20.0, m, look({9.0f, 12.0f, 14.0f}));
  CHECK(o3.looks == 1);
  CHECK(o3.id == 3);
  REQUIRE(f.objects().size() == 2);
  // the nearest object wins when two are within the radius
  const FusedObject& o4 = f.add(4, 14.0, 20.0, m, look({9.0f, 12.0f, 14.0f}));
  CHECK(o4.id == 3);
  CHECK(o4.looks == 2);
}

TEST_CASE("look fusion: the radius must be positive") {
  CHECK_THROWS_AS(LookFusion(0.0), std::invalid_argument);
  CHECK_THROWS_AS(LookFusion(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sonarloop::atr
