/**
 * @file
 * Space-filling-curve partition of DDA blocks (block_partition.h).
 */
#include <rockdda/dda/block_partition.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockdda::dda
{
  int
  BlockPartition::owner(const int b) const
  {
    const int p = position[b];
    return static_cast<int>(std::upper_bound(first.begin(), first.end(), p)
                            - first.begin())
           - 1;
  }



  std::uint64_t
  hilbert_index(std::uint32_t x, std::uint32_t y, const int bits)
  {
    // Descend the quadrants from the coarsest: each adds its rank along
    // the curve (0 lower left, 1 upper left, 2 upper right, 3 lower right
    // of the current, suitably turned, square) times the cells below it,
    // then turns the coordinates into the frame of the sub-curve.
    const std::uint32_t side = std::uint32_t(1) << bits;
    std::uint64_t       d    = 0;
    for (std::uint32_t s = side >> 1; s > 0; s >>= 1)
      {
        const std::uint32_t rx = (x & s) != 0 ? 1 : 0;
        const std::uint32_t ry = (y & s) != 0 ? 1 : 0;
        d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
        if (ry == 0)
          {
            if (rx == 1)
              {
                x = side - 1 - x;
                y = side - 1 - y;
              }
            std::swap(x, y);
          }
      }
    return d;
  }



  BlockPartition
  partition_blocks(const std::vector<geometry::Point> &centroids,
                   const int                           n_parts)
  {
    if (n_parts < 1)
      throw std::invalid_argument("partition_blocks: " + std::to_string(n_parts)
                                  + " parts; valid: >= 1");
    const int      n = static_cast<int>(centroids.size());
    BlockPartition result;
    result.order.resize(n);
    std::iota(result.order.begin(), result.order.end(), 0);
    if (n > 0)
      {
        geometry::Point lo = centroids[0], hi = centroids[0];
        for (const auto &c : centroids)
          {
            lo = lo.cwiseMin(c);
            hi = hi.cwiseMax(c);
          }
        // One square box, so that the curve's cells are square.
        const double  extent = std::max((hi - lo).maxCoeff(), 1e-300);
        constexpr int bits   = 16;
        const double  cells  = static_cast<double>(1u << bits);
        std::vector<std::uint64_t> key(n);
        for (int b = 0; b < n; ++b)
          {
            const auto cell = [&](const double v) {
              const double c = std::floor(v / extent * cells);
              return static_cast<std::uint32_t>(std::clamp(c, 0., cells - 1.));
            };
            key[b] = hilbert_index(cell(centroids[b].x() - lo.x()),
                                   cell(centroids[b].y() - lo.y()),
                                   bits);
          }
        std::sort(result.order.begin(),
                  result.order.end(),
                  [&](const int a, const int b) {
                    return key[a] != key[b] ? key[a] < key[b] : a < b;
                  });
      }
    result.position.resize(n);
    for (int p = 0; p < n; ++p)
      result.position[result.order[p]] = p;
    result.first.resize(n_parts + 1);
    for (int r = 0; r <= n_parts; ++r)
      result.first[r]
        = static_cast<int>((static_cast<long long>(n) * r) / n_parts);
    return result;
  }
} // namespace rockdda::dda
