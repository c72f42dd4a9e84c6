#include <rockdda/seismic/analyses.h>
#include <rockdda/seismic/synthetic_analysis.h>

namespace rockdda::seismic
{
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(internal::make_record_analysis());
    list.push_back(make_synthetic_analysis());
    return list;
  }
} // namespace rockdda::seismic
