#include "io/csv_series.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace cgdem::io {
namespace {

std::string join(const std::vector<std::string>& cols) {
  std::string s;
  for (size_t i = 0; i < cols.size(); ++i) {
    if (i) s += ',';
    s += cols[i];
  }
  return s;
}

// Reads an existing series; cuts an incomplete last line; returns its column line ("" if none).
std::string prepare_existing(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const size_t keep = text.empty() || text.back() == '\n' ? text.size() : text.rfind('\n') + 1;  // npos+1 == 0
  if (keep != text.size()) std::filesystem::resize_file(path, keep);
  std::istringstream lines(text.substr(0, keep));
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] != '#') return line;
  }
  return "";
}

}  // namespace

CsvSeries::CsvSeries(std::string path, std::vector<std::string> columns, const std::vector<std::string>& header_comments,
                     bool append)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw Error("CSV series '" + path_ + "': no columns");
  for (const std::string& c : columns_)
    if (c.empty() || c.find_first_of(",\n\r\"") != std::string::npos || c[0] == '#')
      throw Error("CSV series '" + path_ + "': bad column name '" + c + "'");
  const std::string column_line = join(columns_);
  bool fresh = true;
  if (append) {
    std::error_code ec;
    if (std::filesystem::exists(path_, ec)) {
      const std::string existing = prepare_existing(path_);
      if (!existing.empty() && existing != column_line)
        throw Error("CSV series '" + path_ + "': cannot append, its columns are '" + existing + "' but '" +
                    column_line + "' were requested");
      fresh = existing.empty() && std::filesystem::file_size(path_) == 0;
      if (existing.empty() && !fresh)
        throw Error("CSV series '" + path_ + "': cannot append, the file has no column line");
    }
  }
  file_ = std::fopen(path_.c_str(), fresh ? "w" : "a");
  if (!file_) throw Error("cannot open CSV series '" + path_ + "': " + std::strerror(errno));
  write_comments(header_comments);
  if (fresh) write_text(column_line + "\n");
  flush();
}

CsvSeries::~CsvSeries() {
  if (file_) std::fclose(file_);
}

void CsvSeries::write_comments(const std::vector<std::string>& comments) {
  std::string text;
  for (const std::string& c : comments) {
    std::istringstream lines(c);
    for (std::string line; std::getline(lines, line);) text += "# " + line + "\n";
    if (c.empty()) text += "#\n";
  }
  write_text(text);
}

void CsvSeries::write_text(const std::string& text) {
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw Error("write to CSV series '" + path_ + "' failed: " + std::strerror(errno));
}

void CsvSeries::row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw Error("CSV series '" + path_ + "': row has " + std::to_string(values.size()) + " values for " +
                std::to_string(columns_.size()) + " columns");
  std::string line;
  char buf[32];
  for (size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, i ? ",%.10g" : "%.10g", values[i]);
    line += buf;
  }
  line += '\n';
  write_text(line);
}

void CsvSeries::flush() {
  if (std::fflush(file_) != 0) throw Error("flush of CSV series '" + path_ + "' failed: " + std::strerror(errno));
}

}  // namespace cgdem::io
