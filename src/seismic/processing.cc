#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/processing.h>

#include <Eigen/Dense>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockdda::seismic
{
  void
  remove_baseline(Record &record, const unsigned int degree)
  {
    if (degree > 2)
      throw std::invalid_argument("remove_baseline: degree 0, 1 or 2");
    auto             &a = record.acceleration;
    const std::size_t n = a.size();
    if (n < 2)
      return;
    const double      h = record.dt, T = h * (n - 1);
    const std::size_t m = degree + 1;
    // Columns: the trapezoidal integrals B_k(t_i) of the basis (t/T)^k, so
    // that the corrected velocity is exactly v - B c (the trapezoidal rule
    // is linear).
    Eigen::MatrixXd B(n, m);
    Eigen::VectorXd v(n);
    B.row(0).setZero();
    v(0)         = 0.;
    const auto q = [&](const std::size_t i, const std::size_t k) {
      return std::pow(i * h / T, static_cast<double>(k));
    };
    for (std::size_t i = 1; i < n; ++i)
      {
        v(i) = v(i - 1) + 0.5 * h * (a[i - 1] + a[i]);
        for (std::size_t k = 0; k < m; ++k)
          B(i, k) = B(i - 1, k) + 0.5 * h * (q(i - 1, k) + q(i, k));
      }
    // Least squares with the constraint B(n-1,:) c = v(n-1) (KKT system).
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m + 1, m + 1);
    Eigen::VectorXd r(m + 1);
    K.topLeftCorner(m, m)    = B.transpose() * B;
    K.block(0, m, m, 1)      = B.row(n - 1).transpose();
    K.block(m, 0, 1, m)      = B.row(n - 1);
    r.head(m)                = B.transpose() * v;
    r(m)                     = v(n - 1);
    const Eigen::VectorXd cl = K.fullPivLu().solve(r);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < m; ++k)
        a[i] -= cl(k) * q(i, k);
  }



  double
  low_pass_gain(const double f, const double corner, const unsigned int order)
  {
    return 1. / std::sqrt(1. + std::pow(std::abs(f) / corner, 2. * order));
  }



  double
  high_pass_gain(const double f, const double corner, const unsigned int order)
  {
    if (f == 0.)
      return 0.;
    return 1. / std::sqrt(1. + std::pow(corner / std::abs(f), 2. * order));
  }



  double
  filter_padding(const double       high_pass,
                 const double       low_pass,
                 const unsigned int order)
  {
    const double fc = high_pass > 0. ? high_pass : low_pass;
    return fc > 0. ? 0.5 * 1.5 * order / fc : 0.;
  }



  double
  filter_acausal(Record            &record,
                 const double       high_pass,
                 const double       low_pass,
                 const unsigned int order,
                 const bool         keep_padding)
  {
    if (!(high_pass >= 0.) || !(low_pass >= 0.) || order < 1)
      throw std::invalid_argument("filter_acausal: corners >= 0, order >= 1");
    if (high_pass == 0. && low_pass == 0.)
      return 0.;
    const std::size_t pad = static_cast<std::size_t>(
      std::ceil(filter_padding(high_pass, low_pass, order) / record.dt));
    const std::size_t   n = record.acceleration.size();
    std::vector<double> x(n + 2 * pad, 0.);
    std::copy(record.acceleration.begin(),
              record.acceleration.end(),
              x.begin() + pad);
    const std::size_t nfft = fast_fft_size(x.size());
    auto              X    = forward_real_fft(x, nfft);
    for (std::size_t k = 0; k < X.size(); ++k)
      {
        const double f = k / (nfft * record.dt);
        double       g = 1.;
        if (high_pass > 0.)
          g *= high_pass_gain(f, high_pass, order);
        if (low_pass > 0.)
          g *= low_pass_gain(f, low_pass, order);
        X[k] *= g;
      }
    const auto y = inverse_real_fft(X, nfft);
    if (keep_padding)
      {
        record.acceleration.assign(y.begin(), y.begin() + x.size());
        return pad * record.dt;
      }
    record.acceleration.assign(y.begin() + pad, y.begin() + pad + n);
    return 0.;
  }



  Record
  resample(const Record &record, const double dt, const ResampleMethod method)
  {
    if (!(dt > 0.) || !std::isfinite(dt))
      throw InputError(record.name + ": the resampling step must be > 0 s");
    Record out          = record;
    out.dt              = dt;
    const std::size_t n = record.acceleration.size();
    if (n < 2)
      return out;
    const std::size_t n_out = static_cast<std::size_t>(std::floor(
                                (n - 1) * record.dt / dt * (1. + 1e-12)))
                              + 1;
    if (method == ResampleMethod::linear)
      {
        out.acceleration.resize(n_out);
        for (std::size_t i = 0; i < n_out; ++i)
          out.acceleration[i] = record.at(i * dt);
        return out;
      }
    // New samples per old sample, r = p / q.
    const double r = record.dt / dt;
    std::size_t  q = 1;
    for (; q <= 1000; ++q)
      if (std::abs(r * q - std::round(r * q)) < 1e-9 * r * q)
        break;
    if (q > 1000)
      throw InputError(record.name + ": Fourier resampling from dt = "
                       + io::format_number(record.dt, 8) + " s to "
                       + io::format_number(dt, 8)
                       + " s needs a ratio of integers up to 1000; use "
                         "linear resampling or another step");
    const std::size_t p = static_cast<std::size_t>(std::llround(r * q));
    // Zero padding (10 %) so that the periodic extension does not join the
    // record's end to its start; a multiple of q so that n2 p / q is whole.
    const std::size_t pad = std::max<std::size_t>(16, n / 10);
    std::size_t       n2  = fast_fft_size(n + pad);
    n2                    = ((n2 + q - 1) / q) * q;
    const std::size_t m   = n2 * p / q;
    const auto        X   = forward_real_fft(record.acceleration, n2);
    std::vector<std::complex<double>> Y(m / 2 + 1, 0.);
    if (m >= n2)
      {
        for (std::size_t k = 0; k < X.size(); ++k)
          Y[k] = X[k];
        // The Nyquist term of an even-length sequence splits between +f
        // and -f when the band is widened.
        if (m > n2 && n2 % 2 == 0)
          Y[n2 / 2] *= 0.5;
      }
    else
      for (std::size_t k = 0; k < Y.size(); ++k)
        Y[k] = (m % 2 == 0 && k == m / 2) ? 0. : X[k];
    auto y = inverse_real_fft(Y, m);
    out.acceleration.assign(y.begin(), y.begin() + std::min(n_out, m));
    for (double &v : out.acceleration)
      v *= static_cast<double>(m) / n2;
    return out;
  }



  Record
  process(const Record            &record,
          const ProcessingOptions &options,
          ProcessingReport        *report)
  {
    Record             out = record;
    std::ostringstream d;
    if (options.resample_dt > 0.)
      {
        out = resample(out, options.resample_dt, options.method);
        d << "resampled to dt = " << options.resample_dt << " s ("
          << (options.method == ResampleMethod::fourier ? "Fourier" : "linear")
          << ")";
      }
    if (options.baseline_degree >= 0)
      {
        remove_baseline(out, options.baseline_degree);
        d << (d.str().empty() ? "" : ", ") << "baseline of degree "
          << options.baseline_degree << " removed";
      }
    double padding = 0.;
    if (options.high_pass > 0. || options.low_pass > 0.)
      {
        padding = filter_acausal(out,
                                 options.high_pass,
                                 options.low_pass,
                                 options.order,
                                 options.keep_padding);
        d << (d.str().empty() ? "" : ", ") << "acausal Butterworth order "
          << options.order;
        if (options.high_pass > 0.)
          d << ", high-pass " << options.high_pass << " Hz";
        if (options.low_pass > 0.)
          d << ", low-pass " << options.low_pass << " Hz";
        d << ", padding "
          << io::format_number(filter_padding(options.high_pass,
                                              options.low_pass,
                                              options.order),
                               4)
          << " s at each end " << (options.keep_padding ? "kept" : "removed");
      }
    if (report != nullptr)
      {
        report->padding     = padding;
        report->description = d.str().empty() ? "unprocessed" : d.str();
      }
    return out;
  }
} // namespace rockdda::seismic
