#include <rockdda/io/error.h>
#include <rockdda/seismic/fft.h>

#include <algorithm>
#include <fftw3.h>
#include <stdexcept>

namespace rockdda::seismic
{
  namespace
  {
    /// Frees FFTW buffers and plans on scope exit.
    struct FftwBuffers
    {
      double       *real    = nullptr;
      fftw_complex *complex = nullptr;
      fftw_plan     plan    = nullptr;

      FftwBuffers(const std::size_t n)
      {
        real    = fftw_alloc_real(n);
        complex = fftw_alloc_complex(n / 2 + 1);
        if (real == nullptr || complex == nullptr)
          throw std::runtime_error("FFTW: out of memory for a transform of "
                                   + std::to_string(n) + " samples");
      }

      ~FftwBuffers()
      {
        if (plan != nullptr)
          fftw_destroy_plan(plan);
        fftw_free(real);
        fftw_free(complex);
      }

      FftwBuffers(const FftwBuffers &) = delete;
      FftwBuffers &
      operator=(const FftwBuffers &)
        = delete;
    };
  } // namespace



  std::size_t
  fast_fft_size(const std::size_t n)
  {
    for (std::size_t m = std::max<std::size_t>(n, 1);; ++m)
      {
        std::size_t r = m;
        for (const std::size_t p : {2, 3, 5, 7})
          while (r % p == 0)
            r /= p;
        if (r == 1)
          return m;
      }
  }



  std::vector<std::complex<double>>
  forward_real_fft(const std::vector<double> &x, const std::size_t n)
  {
    if (n < x.size() || n == 0)
      throw std::invalid_argument("forward_real_fft: length below the data");
    FftwBuffers b(n);
    // FFTW_ESTIMATE: the plan does not overwrite the buffers and the result
    // does not depend on timing measurements (runs are reproducible).
    b.plan = fftw_plan_dft_r2c_1d(static_cast<int>(n),
                                  b.real,
                                  b.complex,
                                  FFTW_ESTIMATE);
    std::copy(x.begin(), x.end(), b.real);
    std::fill(b.real + x.size(), b.real + n, 0.);
    fftw_execute(b.plan);
    std::vector<std::complex<double>> X(n / 2 + 1);
    for (std::size_t k = 0; k < X.size(); ++k)
      X[k] = {b.complex[k][0], b.complex[k][1]};
    return X;
  }



  std::vector<double>
  inverse_real_fft(const std::vector<std::complex<double>> &spectrum,
                   const std::size_t                        n)
  {
    if (spectrum.size() != n / 2 + 1 || n == 0)
      throw std::invalid_argument("inverse_real_fft: spectrum size is not "
                                  "n/2 + 1");
    FftwBuffers b(n);
    b.plan = fftw_plan_dft_c2r_1d(static_cast<int>(n),
                                  b.complex,
                                  b.real,
                                  FFTW_ESTIMATE);
    for (std::size_t k = 0; k < spectrum.size(); ++k)
      {
        b.complex[k][0] = spectrum[k].real();
        b.complex[k][1] = spectrum[k].imag();
      }
    fftw_execute(b.plan);
    std::vector<double> x(b.real, b.real + n);
    for (double &v : x)
      v /= static_cast<double>(n);
    return x;
  }
} // namespace rockdda::seismic
