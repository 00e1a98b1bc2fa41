#pragma once
// Cuts a serial byte stream into NMEA lines. A line starts at '$' and ends at CR or LF; bytes between lines are
// garbage, a '$' inside a line means the line was cut short (truncated), bytes outside printable ASCII spoil
// their line, and a line longer than the limit is dropped up to its end. Each case is counted; nothing throws.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "common/time.hpp"

namespace fsd {

class NmeaLineSplitter {
 public:
  struct Counters {
    std::uint64_t bytes = 0;
    std::uint64_t garbage_bytes = 0;  // outside any line
    std::uint64_t overlong_lines = 0;
    std::uint64_t truncated_lines = 0;      // a new '$' arrived before the line ended
    std::uint64_t bad_character_lines = 0;  // contained a byte outside 0x20..0x7E
  };

  explicit NmeaLineSplitter(std::size_t max_line_length) : max_(max_line_length) { line_.reserve(max_ + 1); }

  // Calls on_line(std::string_view line, Stamp t) for each complete line (without CR/LF), t being the receive
  // time of the chunk in which its '$' arrived.
  template <class OnLine>
  void feed(std::span<const std::uint8_t> bytes, Stamp t, OnLine&& on_line) {
    counters_.bytes += bytes.size();
    for (const std::uint8_t b : bytes) {
      const char c = static_cast<char>(b);
      if (c == '$') {
        if (state_ == State::InLine) ++counters_.truncated_lines;
        start_line(t);
      } else if (c == '\r' || c == '\n') {
        if (state_ == State::InLine) {
          if (bad_char_)
            ++counters_.bad_character_lines;
          else
            on_line(std::string_view(line_), line_stamp_);
        }
        state_ = State::Idle;
      } else if (state_ == State::Idle) {
        ++counters_.garbage_bytes;
      } else if (state_ == State::InLine) {
        if (b < 0x20 || b > 0x7E) bad_char_ = true;
        line_ += c;
        if (line_.size() > max_) {
          ++counters_.overlong_lines;
          state_ = State::Discarding;
        }
      }
    }
  }

  const Counters& counters() const { return counters_; }

 private:
  enum class State { Idle, InLine, Discarding };
  void start_line(Stamp t) {
    line_.assign(1, '$');
    line_stamp_ = t;
    bad_char_ = false;
    state_ = State::InLine;
  }

  std::size_t max_;
  std::string line_;
  Stamp line_stamp_ = 0;
  bool bad_char_ = false;
  State state_ = State::Idle;
  Counters counters_;
};

}  // namespace fsd
