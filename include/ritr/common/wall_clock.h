#pragma once
// Wall-clock timing for the step reports: seconds since a time point, and a scope that adds
// its duration to a counter.
#include <chrono>

namespace ritr
{
  inline double seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  class ScopedTimer
  {
  public:
    explicit ScopedTimer(double &total) : total_(total), start_(std::chrono::steady_clock::now()) {}
    ~ScopedTimer() { total_ += seconds_since(start_); }
    ScopedTimer(const ScopedTimer &)            = delete;
    ScopedTimer &operator=(const ScopedTimer &) = delete;

  private:
    double                               &total_;
    std::chrono::steady_clock::time_point start_;
  };
} // namespace ritr
