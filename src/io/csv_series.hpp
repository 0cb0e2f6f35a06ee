// CsvSeries: a time series of scalar diagnostics as CSV text (energy budgets, fill level,
// pressure drop ...), one row per output step, readable by numpy/pandas (comment='#').
//
//   # <header comment lines: resolved configuration, git revision, ...>
//   col1,col2,...
//   v1,v2,...            each value %.10g; every row is formatted completely in memory
//                        and handed to the C library in one write, then flushed on flush()
//
// Append mode (restart): an existing file is continued. Its column line must equal the
// requested columns (else cgdem::Error); a trailing incomplete line left by a crash is cut
// off first; the new header comments are appended as '#' lines. A missing or empty file is
// started fresh. Rows written after the checkpoint by the crashed run are NOT removed: the
// caller filters by time when analysing, or starts the series fresh.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

namespace cgdem::io {

class CsvSeries {
 public:
  CsvSeries(std::string path, std::vector<std::string> columns, const std::vector<std::string>& header_comments = {},
            bool append = false);
  ~CsvSeries();
  CsvSeries(const CsvSeries&) = delete;
  CsvSeries& operator=(const CsvSeries&) = delete;

  // One value per column (cgdem::Error otherwise); non-finite values are written as nan/inf.
  void row(const std::vector<double>& values);
  void flush();  // fflush: rows so far reach the operating system

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  void write_text(const std::string& text);
  void write_comments(const std::vector<std::string>& comments);

  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
};

}  // namespace cgdem::io
