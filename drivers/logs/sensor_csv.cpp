#include "drivers/logs/sensor_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace fsd {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string printable(std::string_view s) {
  std::string out;
  for (const char c : s.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > 40) out += "...";
  return out;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& c : v) s += (s.empty() ? "" : ",") + c;
  return s;
}

}  // namespace

SensorCsv parse_sensor_csv(std::string_view text, const std::string& origin, const SensorCsvSpec& spec) {
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw SensorCsvError(origin + ":" + std::to_string(line) + ": " + what);
  };
  SensorCsv out;
  out.columns = spec.columns.size();
  std::size_t line_no = 0;
  bool header = false;
  double previous_t = 0;
  std::size_t previous_line = 0;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    line = trim(line);
    if (line.empty()) continue;
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(
          trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (!header) {
      bool same = fields.size() == spec.columns.size();
      for (std::size_t i = 0; same && i < fields.size(); ++i) same = fields[i] == spec.columns[i];
      if (!same) fail(line_no, "header '" + printable(line) + "' is not the expected '" + joined(spec.columns) + "'");
      header = true;
      continue;
    }
    if (fields.size() != out.columns)
      fail(line_no, std::to_string(fields.size()) + " fields, expected " + std::to_string(out.columns));
    if (out.rows() >= spec.max_rows) fail(line_no, "more than " + std::to_string(spec.max_rows) + " rows");
    for (std::size_t i = 0; i < fields.size(); ++i) {
      double v = 0;
      const auto f = fields[i];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (f.empty() || ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v))
        fail(line_no, "column " + spec.columns[i] + ": '" + printable(f) + "' is not a finite number");
      out.values.push_back(v);
    }
    const double t = out.values[out.values.size() - out.columns];
    if (out.rows() > 1) {
      if (!(t > previous_t)) {
        std::ostringstream m;
        m.precision(16);
        m << "time " << t << " does not increase (line " << previous_line << ": " << previous_t << ")";
        fail(line_no, m.str());
      }
      if (spec.max_gap_s > 0 && t - previous_t > spec.max_gap_s) {
        std::ostringstream m;
        m.precision(6);
        m << "gap of " << t - previous_t << " s since line " << previous_line << " (at most " << spec.max_gap_s
          << " s)";
        fail(line_no, m.str());
      }
    }
    previous_t = t;
    previous_line = line_no;
  }
  if (!header) fail(line_no, "empty: no header '" + joined(spec.columns) + "'");
  if (out.rows() == 0) fail(line_no, "no data rows");
  return out;
}

SensorCsv load_sensor_csv(const std::filesystem::path& file, const SensorCsvSpec& spec) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw SensorCsvError(file.string() + ": cannot read: " + ec.message());
  if (size > spec.max_bytes)
    throw SensorCsvError(file.string() + ": " + std::to_string(size) + " bytes, more than " +
                         std::to_string(spec.max_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SensorCsvError(file.string() + ": cannot open");
  std::string text(size, '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) throw SensorCsvError(file.string() + ": read failed");
  return parse_sensor_csv(text, file.string(), spec);
}

}  // namespace fsd
