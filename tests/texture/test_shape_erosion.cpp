#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/shape_erosion.hpp"

using namespace forensim;

TEST(ShapeErosion, KernelWidthIsOddAsEquation31) {
  EXPECT_EQ(erosion_kernel_width(1), 3);
  EXPECT_EQ(erosion_kernel_width(2), 3);
  EXPECT_EQ(erosion_kernel_width(3), 5);
  EXPECT_EQ(erosion_kernel_width(4), 5);
  EXPECT_EQ(erosion_kernel_width(10), 11);
  const std::vector<int> widths = random_erosion_widths(40, 30, 3, 10, 4);
  ASSERT_EQ(widths.size(), 1200u);
  bool saw_low = false, saw_high = false;
  for (int w : widths) {
    EXPECT_EQ(w % 2, 1);
    EXPECT_GE(w, 5);   // kernelWidth(3)
    EXPECT_LE(w, 11);  // kernelWidth(10)
    saw_low |= w == 5;
    saw_high |= w == 11;
  }
  EXPECT_TRUE(saw_low && saw_high);
  EXPECT_THROW(random_erosion_widths(4, 4, 0, 3, 1), InputError);
  EXPECT_THROW(random_erosion_widths(4, 4, 5, 3, 1), InputError);
}

TEST(ShapeErosion, EqualsTheBruteForceMinimumAlongRowsAndColumns) {
  Image shape(23, 17, 1);
  RandomStream rng(6, 0);
  for (float& v : shape.data()) v = rng.uniform() < 0.8 ? 1.0f : static_cast<float>(rng.uniform());
  const std::vector<int> widths = random_erosion_widths(23, 17, 1, 6, 12);
  for (ErosionAxis axis : {ErosionAxis::x, ErosionAxis::y}) {
    const Image eroded = erode_shape(shape, widths, axis);
    for (int y = 0; y < 17; ++y)
      for (int x = 0; x < 23; ++x) {
        const int edge = widths[static_cast<std::size_t>(y * 23 + x)] / 2;
        float expected = 1e30f;  // outside pixels count as the highest value
        for (int k = -edge; k <= edge; ++k) {
          const int sx = axis == ErosionAxis::x ? x + k : x, sy = axis == ErosionAxis::y ? y + k : y;
          if (sx >= 0 && sx < 23 && sy >= 0 && sy < 17) expected = std::min(expected, shape.at(sx, sy));
        }
        ASSERT_EQ(eroded.at(x, y), expected) << x << "," << y;
      }
  }
}

TEST(ShapeErosion, BinaryShapesGiveTheSameResultAsExplicitWidths) {
  // 0/1 shapes take the linear-time path; it must equal Algorithm 3.1 with the same random widths.
  Image shape(57, 41, 1, 0.0f, PixelEncoding::data);
  RandomStream rng(9, 0);
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 57; ++x) {
      const double dx = (x - 28.0) / 22.0, dy = (y - 20.0) / 15.0;
      shape.at(x, y) = dx * dx + dy * dy < 1.0 && rng.uniform() < 0.97 ? 1.0f : 0.0f;
    }
  for (const auto& [lo, hi] : {std::pair{3, 5}, std::pair{3, 10}, std::pair{1, 1}, std::pair{6, 20}}) {
    for (ErosionAxis axis : {ErosionAxis::x, ErosionAxis::y}) {
      const Image fast = erode_shape(shape, lo, hi, 31, axis);
      const Image brute = erode_shape(shape, random_erosion_widths(57, 41, lo, hi, 31), axis);
      ASSERT_EQ(fast.data(), brute.data()) << lo << ".." << hi;
    }
  }
  EXPECT_THROW(erode_shape(shape, 5, 3, 1), InputError);
}

TEST(ShapeErosion, ShrinksADiscOnlyAlongTheAxisAndIsDeterministic) {
  Image disc(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) disc.at(x, y) = (x - 31.5) * (x - 31.5) + (y - 31.5) * (y - 31.5) < 400 ? 1.0f : 0.0f;
  const int previous = thread_count();
  set_thread_count(1);
  const Image a = erode_shape(disc, 3, 10, 5);
  set_thread_count(2);
  const Image b = erode_shape(disc, 3, 10, 5);
  set_thread_count(previous);
  EXPECT_EQ(a.data(), b.data());
  double before = 0, after = 0;
  for (std::size_t i = 0; i < disc.data().size(); ++i) {
    before += disc.data()[i];
    after += a.data()[i];
    EXPECT_LE(a.data()[i], disc.data()[i]);  // erosion never grows the shape
  }
  EXPECT_LT(after, before);
  EXPECT_GT(after, 0.7 * before);
  // The middle row keeps its centre, and a full-width column through the centre is unchanged (x kernel).
  EXPECT_EQ(a.at(32, 32), 1.0f);
  for (int y = 0; y < 64; ++y) EXPECT_LE(a.at(32, y), disc.at(32, y));
  const std::vector<int> bad(10, 3);
  EXPECT_THROW(erode_shape(disc, bad), InputError);
  EXPECT_THROW(erode_shape(Image(2, 1, 1), std::vector<int>{3, 4}), InputError);
}
