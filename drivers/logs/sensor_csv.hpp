#pragma once
// Sensor logs as CSV text (the ../shared/data/amz_2017 format, `fsd localize`): a header naming the columns, then
// one sample a row, all numbers, time in the first column. Untrusted input: a header that is not the expected one
// (another log passed by mistake), a row with the wrong number of fields or a field that is not a finite number,
// a time that does not increase, a gap between samples longer than allowed: SensorCsvError naming "FILE:LINE".
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fsd {

class SensorCsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SensorCsvSpec {
  std::vector<std::string> columns;  // the header, exactly (time first)
  double max_gap_s = 0;              // > 0: a longer gap between two rows is an error
  std::size_t max_rows = 20'000'000;
  std::uintmax_t max_bytes = 1ull << 30;
};

struct SensorCsv {
  std::vector<double> values;  // row-major, columns.size() per row
  std::size_t columns = 0;
  std::size_t rows() const { return columns ? values.size() / columns : 0; }
  double at(std::size_t row, std::size_t col) const { return values[row * columns + col]; }
};

// `origin` names the text in messages ("FILE:LINE: problem"). Windows line ends and a final line without one are
// fine; blank lines are skipped.
SensorCsv parse_sensor_csv(std::string_view text, const std::string& origin, const SensorCsvSpec& spec);
// Reads and parses a file; throws SensorCsvError when it is missing, unreadable or too large.
SensorCsv load_sensor_csv(const std::filesystem::path& file, const SensorCsvSpec& spec);

}  // namespace fsd
