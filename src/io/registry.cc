#include <rockdda/analytical/analyses.h>
#include <rockdda/coupling/analyses.h>
#include <rockdda/dda/analyses.h>
#include <rockdda/dda3d/analyses.h>
#include <rockdda/io/analysis.h>
#include <rockdda/seismic/analyses.h>
#include <rockdda/structure/analyses.h>
#include <rockdda/thermal/analyses.h>

namespace rockdda::io
{
  std::vector<std::unique_ptr<Analysis>>
  all_analyses()
  {
    std::vector<std::unique_ptr<Analysis>> list;
    for (auto &a : analytical::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : thermal::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : dda::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : dda3d::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : structure::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : coupling::make_analyses())
      list.push_back(std::move(a));
    for (auto &a : seismic::make_analyses())
      list.push_back(std::move(a));
    return list;
  }
} // namespace rockdda::io
