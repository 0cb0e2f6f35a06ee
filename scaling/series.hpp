// Time series on different time bases brought onto one and compared.
//
// Resampling: piecewise-linear interpolation of (t_i, y_i) at the times tau_j, which must
// lie within [t_0, t_{n-1}] (exact at the samples; error <= h^2 max|y''| / 8 between them).
// The common time base of a study is the reference run's times inside the span every run
// covers.
//
// Distances, with trapezoidal weights w_j on the common times (non-uniform spacing):
//   max deviation     D_inf = max_j |a_j - b_j| / S                      (S: a stated scale)
//   normalized L2     D_2   = sqrt( sum_j w_j (a_j - b_j)^2 / sum_j w_j b_j^2 )   (b: reference)
// and the peak of a series: the largest sample and its time.
#pragma once
#include <cstddef>
#include <vector>

namespace cgdem::scaling {

struct Series {
  std::vector<double> t, y;
};

// y(t) at each of `times`; throws cgdem::Error if a time lies outside the series' span or
// the series is empty or not increasing in t.
std::vector<double> resample(const Series& s, const std::vector<double>& times);

// The reference's times within [max of the starts, min of the ends] of all `spans`.
std::vector<double> common_times(const std::vector<double>& reference, const std::vector<Series>& all);

std::vector<double> trapezoid_weights(const std::vector<double>& t);

// max_j |a_j - b_j| and the index where it is reached (a.size() == b.size() > 0).
struct MaxDeviation {
  double value = 0;
  std::size_t index = 0;
};
MaxDeviation max_abs_deviation(const std::vector<double>& a, const std::vector<double>& b);

// D_2 above; returns NaN when the reference is zero everywhere.
double normalized_l2(const std::vector<double>& t, const std::vector<double>& a, const std::vector<double>& ref);

struct Peak {
  double t = 0, value = 0;
};
Peak peak(const Series& s);  // the largest y (first one on ties); throws on an empty series

}  // namespace cgdem::scaling
