#pragma once
// A tiny metrics registry rendered in the Prometheus text format (version 0.0.4) at /metrics. The daemon fills it
// (per-stage latency, rates, drops, queue depths, AS state); the web server adds its own (clients, bytes, drops).
// Updating a metric is lock-free so the control thread can do it; registering takes a lock and happens at start.
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace fsd::web {

using Labels = std::vector<std::pair<std::string, std::string>>;

class Counter {
 public:
  void inc(std::uint64_t n = 1) { v_.fetch_add(n, std::memory_order_relaxed); }
  std::uint64_t value() const { return v_.load(std::memory_order_relaxed); }

 private:
  std::atomic<std::uint64_t> v_{0};
};

class Gauge {
 public:
  void set(double v) { v_.store(v, std::memory_order_relaxed); }
  void add(double d) { v_.fetch_add(d, std::memory_order_relaxed); }
  double value() const { return v_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> v_{0.0};
};

// Quantiles over a sliding window of the latest observations, plus the running sum and count of all of them.
class Summary {
 public:
  explicit Summary(std::size_t window = 1024);
  void observe(double v);
  struct Snapshot {
    std::uint64_t count = 0;
    double sum = 0, p50 = 0, p90 = 0, p99 = 0, max = 0;  // quantiles and max of the window; 0 when empty
  };
  Snapshot snapshot() const;

 private:
  std::vector<std::atomic<double>> ring_;
  std::atomic<std::uint64_t> count_{0};
  std::atomic<double> sum_{0.0};
};

class Metrics {
 public:
  // Each returns the metric of that name and label set, creating it on first use; the reference stays valid for
  // the registry's lifetime. Registering a name again with another type throws std::logic_error, as does a name
  // or label name outside [a-zA-Z_:][a-zA-Z0-9_:]*.
  Counter& counter(const std::string& name, const std::string& help, const Labels& labels = {});
  Gauge& gauge(const std::string& name, const std::string& help, const Labels& labels = {});
  Summary& summary(const std::string& name, const std::string& help, const Labels& labels = {});
  // A gauge computed when /metrics is read (queue depths, client counts). The function must be thread-safe.
  void gauge_callback(const std::string& name, const std::string& help, std::function<double()> fn,
                      const Labels& labels = {});

  std::string render() const;

 private:
  enum class Type { Counter, Gauge, Summary };
  struct Series {
    std::unique_ptr<Counter> counter;
    std::unique_ptr<Gauge> gauge;
    std::unique_ptr<Summary> summary;
    std::function<double()> callback;
  };
  struct Family {
    Type type;
    std::string help;
    std::map<std::string, Series> series;  // key: rendered label set
  };
  Series& series(const std::string& name, const std::string& help, Type type, const Labels& labels);

  mutable std::mutex m_;
  std::map<std::string, Family> families_;
};

}  // namespace fsd::web
