#pragma once
// Strict, line-numbered reading of the project's CSV files: "# key=value"
// metadata lines, one header row, then data rows. Every failure names the
// source and the line, so a user can open the file at the right place.

#include <istream>
#include <map>
#include <string>
#include <vector>

namespace hapcine {

class CsvReader {
 public:
  CsvReader(std::istream& in, std::string source_name);

  // Reads the metadata block and the header; throws Error if there is none.
  void ReadPreamble();
  const std::map<std::string, std::string>& metadata() const { return metadata_; }
  const std::vector<std::string>& header() const { return header_; }
  // Column index by name, or -1.
  int Column(const std::string& name) const;
  // Throws unless the header starts with exactly `names`, in order.
  void RequireLeadingColumns(const std::vector<std::string>& names) const;

  // Next data row split into fields; false at end of input. Throws on a row
  // whose field count differs from the header's (a truncated line).
  bool NextRow(std::vector<std::string>* fields);
  int line() const { return line_; }

  // Parsing helpers that throw Error("<source>:<line>", ...) on bad values.
  double Double(const std::vector<std::string>& f, int col, const char* name) const;
  int Int(const std::vector<std::string>& f, int col, const char* name) const;
  [[noreturn]] void Fail(const std::string& reason) const;

 private:
  std::istream& in_;
  std::string source_;
  int line_ = 0;
  std::string pending_;  // first non-metadata line, kept for the header
  std::map<std::string, std::string> metadata_;
  std::vector<std::string> header_;
};

// Fields of one CSV line (RFC 4180 quoting, no embedded newlines): a field
// that starts with '"' runs to the matching '"', with "" for a quote inside,
// and keeps its text as is; an unquoted field is trimmed of spaces, tabs and
// carriage returns. An unterminated quote runs to the end of the line.
std::vector<std::string> SplitCsvLine(const std::string& line);
// `field` as one CSV field: quoted (with "" for a quote inside) when it holds
// a comma, a quote, a line break or leading/trailing white space, so that
// SplitCsvLine reads it back unchanged.
std::string QuoteCsvField(const std::string& field);
// The fields, each through QuoteCsvField, joined by commas (no line break).
std::string JoinCsvLine(const std::vector<std::string>& fields);
// Shortest text that reads back to the same double ("%.17g" trimmed).
std::string FormatDouble(double v);
// Shortest text that reads back (strtod, then rounded to float, as the
// readers do) to the same float: for values held at single precision.
std::string FormatFloat(float v);
// Fixed decimals; used for columns with a natural resolution (times, metres).
std::string FormatFixed(double v, int decimals);

}  // namespace hapcine
