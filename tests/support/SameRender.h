#pragma once

// Two renders of one scene that must not differ (a path against the one it stands in for):
// the same bytes and the same set-up counts.

#include <gtest/gtest.h>

#include "TestRender.h"

namespace facet::testing {

inline void expectSameRender(const Rendered& before, const Rendered& after) {
  EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u) << "pixels differ";
  const RenderStats &s = before.stats, &t = after.stats;
  EXPECT_EQ(s.polygonsDrawn, t.polygonsDrawn);
  EXPECT_EQ(s.polygonsCulled, t.polygonsCulled);
  EXPECT_EQ(s.polygonsOutside, t.polygonsOutside);
  EXPECT_EQ(s.polygonsDegenerate, t.polygonsDegenerate);
  EXPECT_EQ(s.polygonsHidden, t.polygonsHidden);
  EXPECT_EQ(s.trianglesBinned, t.trianglesBinned);
  EXPECT_EQ(s.trianglesClipped, t.trianglesClipped);
  EXPECT_EQ(s.fragmentsWritten, t.fragmentsWritten);  // a dropped back face writes none
}

}  // namespace facet::testing
