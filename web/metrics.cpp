#include "web/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace fsd::web {

namespace {

bool valid_name(const std::string& s) {
  if (s.empty()) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':';
    if (!alpha && !(i > 0 && c >= '0' && c <= '9')) return false;
  }
  return true;
}

std::string escape(const std::string& s, bool quote) {
  std::string out;
  for (const char c : s) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else if (quote && c == '"')
      out += "\\\"";
    else
      out += c;
  }
  return out;
}

// `a="x",b="y"` (no braces), so extra labels such as quantile can be appended.
std::string label_body(const Labels& labels) {
  std::string out;
  for (const auto& [k, v] : labels) {
    if (!valid_name(k) || k.find(':') != std::string::npos)
      throw std::logic_error("metrics: bad label name '" + k + "'");
    out += (out.empty() ? "" : ",") + k + "=\"" + escape(v, true) + "\"";
  }
  return out;
}

std::string braces(const std::string& body) { return body.empty() ? "" : "{" + body + "}"; }

std::string number(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  return fmt::format("{}", v);
}

double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  // Nearest rank: the smallest value with at least q of the samples at or below it.
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

Summary::Summary(std::size_t window) : ring_(window ? window : 1) {}

void Summary::observe(double v) {
  const std::uint64_t i = count_.fetch_add(1, std::memory_order_relaxed);
  ring_[i % ring_.size()].store(v, std::memory_order_relaxed);
  sum_.fetch_add(v, std::memory_order_relaxed);
}

Summary::Snapshot Summary::snapshot() const {
  Snapshot s;
  s.count = count_.load(std::memory_order_relaxed);
  s.sum = sum_.load(std::memory_order_relaxed);
  const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(s.count, ring_.size()));
  std::vector<double> values;
  values.reserve(n);
  for (std::size_t i = 0; i < n; ++i) values.push_back(ring_[i].load(std::memory_order_relaxed));
  std::sort(values.begin(), values.end());
  s.p50 = quantile(values, 0.5);
  s.p90 = quantile(values, 0.9);
  s.p99 = quantile(values, 0.99);
  s.max = values.empty() ? 0.0 : values.back();
  return s;
}

Metrics::Series& Metrics::series(const std::string& name, const std::string& help, Type type, const Labels& labels) {
  if (!valid_name(name)) throw std::logic_error("metrics: bad metric name '" + name + "'");
  const std::string key = label_body(labels);
  std::lock_guard lock(m_);
  auto [it, inserted] = families_.try_emplace(name, Family{type, help, {}});
  if (!inserted && it->second.type != type)
    throw std::logic_error("metrics: '" + name + "' registered again with another type");
  return it->second.series[key];
}

Counter& Metrics::counter(const std::string& name, const std::string& help, const Labels& labels) {
  auto& s = series(name, help, Type::Counter, labels);
  std::lock_guard lock(m_);
  if (!s.counter) s.counter = std::make_unique<Counter>();
  return *s.counter;
}

Gauge& Metrics::gauge(const std::string& name, const std::string& help, const Labels& labels) {
  auto& s = series(name, help, Type::Gauge, labels);
  std::lock_guard lock(m_);
  if (s.callback) throw std::logic_error("metrics: '" + name + "' is a callback gauge");
  if (!s.gauge) s.gauge = std::make_unique<Gauge>();
  return *s.gauge;
}

Summary& Metrics::summary(const std::string& name, const std::string& help, const Labels& labels) {
  auto& s = series(name, help, Type::Summary, labels);
  std::lock_guard lock(m_);
  if (!s.summary) s.summary = std::make_unique<Summary>();
  return *s.summary;
}

void Metrics::gauge_callback(const std::string& name, const std::string& help, std::function<double()> fn,
                             const Labels& labels) {
  auto& s = series(name, help, Type::Gauge, labels);
  std::lock_guard lock(m_);
  if (s.gauge) throw std::logic_error("metrics: '" + name + "' is a plain gauge");
  s.callback = std::move(fn);
}

std::string Metrics::render() const {
  std::lock_guard lock(m_);
  std::string out;
  for (const auto& [name, fam] : families_) {
    const char* type = fam.type == Type::Counter ? "counter" : fam.type == Type::Gauge ? "gauge" : "summary";
    out += "# HELP " + name + " " + escape(fam.help, false) + "\n";
    out += "# TYPE " + name + " " + type + "\n";
    for (const auto& [labels, s] : fam.series) {
      if (s.counter) {
        out += name + braces(labels) + " " + std::to_string(s.counter->value()) + "\n";
      } else if (s.gauge || s.callback) {
        out += name + braces(labels) + " " + number(s.gauge ? s.gauge->value() : s.callback()) + "\n";
      } else if (s.summary) {
        const auto snap = s.summary->snapshot();
        const std::string sep = labels.empty() ? "" : ",";
        for (const auto& [q, v] : {std::pair{"0.5", snap.p50}, {"0.9", snap.p90}, {"0.99", snap.p99}})
          out += name + "{" + labels + sep + "quantile=\"" + q + "\"} " + number(v) + "\n";
        out += name + "_sum" + braces(labels) + " " + number(snap.sum) + "\n";
        out += name + "_count" + braces(labels) + " " + std::to_string(snap.count) + "\n";
      }
    }
  }
  return out;
}

}  // namespace fsd::web
