#include <rockdda/seismic/analyses.h>

namespace rockdda::seismic
{
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(internal::make_record_analysis());
    return list;
  }
} // namespace rockdda::seismic
