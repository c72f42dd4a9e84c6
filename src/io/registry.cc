#include <rockdda/analytical/analyses.h>
#include <rockdda/io/analysis.h>

namespace rockdda::io
{
  std::vector<std::unique_ptr<Analysis>>
  all_analyses()
  {
    std::vector<std::unique_ptr<Analysis>> list;
    for (auto &a : analytical::make_analyses())
      list.push_back(std::move(a));
    return list;
  }
} // namespace rockdda::io
