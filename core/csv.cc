#include "core/csv.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/header_value.h"
#include "core/text.h"

namespace hapcine {
namespace {

// The quoted field starting at line[*i] == '"'; leaves *i after its closing quote.
std::string QuotedField(const std::string& line, size_t* i) {
  std::string field;
  for (++*i; *i < line.size(); ++*i) {
    if (line[*i] != '"') {
      field += line[*i];
    } else if (*i + 1 < line.size() && line[*i + 1] == '"') {
      field += '"';
      ++*i;
    } else {
      ++*i;
      break;
    }
  }
  return field;
}

}  // namespace

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string field;
    if (i < line.size() && line[i] == '"') {
      field = QuotedField(line, &i);
      while (i < line.size() && line[i] != ',') ++i;  // white space after the closing quote
    } else {
      const size_t comma = std::min(line.find(',', i), line.size());
      field = TrimBlanks(line.substr(i, comma - i));
      i = comma;
    }
    out.push_back(field);
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return out;
}

std::string QuoteCsvField(const std::string& field) {
  auto blank = [](char c) { return c == ' ' || c == '\t'; };
  const bool plain = field.find_first_of(",\"\r\n") == std::string::npos &&
                     (field.empty() || (!blank(field.front()) && !blank(field.back())));
  if (plain) return field;
  std::string quoted = "\"";
  for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string JoinCsvLine(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + QuoteCsvField(fields[i]);
  return line;
}

std::string FormatDouble(double v) {
  char buf[64];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string FormatFloat(float v) {
  char buf[64];
  for (int precision = 6; precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (static_cast<float>(std::strtod(buf, nullptr)) == v) break;
  }
  return buf;
}

std::string FormatFixed(double v, int decimals) {
  // Sized by snprintf itself: a value the readers accept (1e100) has over a
  // hundred digits in fixed notation, and a cut number would read back wrong.
  std::string s(std::snprintf(nullptr, 0, "%.*f", decimals, v), '\0');
  std::snprintf(s.data(), s.size() + 1, "%.*f", decimals, v);
  // "-0.000000" reads oddly in a spreadsheet.
  if (s[0] == '-' && std::strtod(s.c_str(), nullptr) == 0.0) return FormatFixed(0.0, decimals);
  return s;
}

CsvReader::CsvReader(std::istream& in, std::string source_name)
    : in_(in), source_(std::move(source_name)) {}

void CsvReader::Fail(const std::string& reason) const {
  throw Error(source_ + ":" + std::to_string(line_), reason);
}

void CsvReader::ReadPreamble() {
  std::string raw;
  while (std::getline(in_, raw)) {
    ++line_;
    std::string s = TrimBlanks(raw);
    if (line_ == 1 && s.rfind("\xEF\xBB\xBF", 0) == 0) s = s.substr(3);  // BOM
    if (s.empty()) continue;
    if (s[0] == '#') {
      // "# key=value" (value may hold spaces, e.g. a file name; escaped as in
      // core/header_value.h), or several
      // space-separated pairs on one line ("# width=1920 height=1080 fps=24").
      const std::string body = TrimBlanks(s.substr(1));
      const size_t eq = body.find('=');
      if (eq != std::string::npos && eq > 0) {
        if (body.find('=', eq + 1) == std::string::npos) {
          metadata_[UnescapeHeaderValue(TrimBlanks(body.substr(0, eq)))] =
              UnescapeHeaderValue(TrimBlanks(body.substr(eq + 1)));
        } else {
          size_t pos = 0;
          while (pos < body.size()) {
            size_t end = body.find(' ', pos);
            if (end == std::string::npos) end = body.size();
            const std::string tok = body.substr(pos, end - pos);
            const size_t teq = tok.find('=');
            if (teq != std::string::npos && teq > 0) {
              metadata_[UnescapeHeaderValue(tok.substr(0, teq))] =
                  UnescapeHeaderValue(tok.substr(teq + 1));
            }
            pos = end + 1;
          }
        }
      }
      continue;
    }
    header_ = SplitCsvLine(s);
    return;
  }
  Fail("no header row (empty or metadata-only file)");
}

int CsvReader::Column(const std::string& name) const {
  for (size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return static_cast<int>(i);
  }
  return -1;
}

void CsvReader::RequireLeadingColumns(const std::vector<std::string>& names) const {
  for (size_t i = 0; i < names.size(); ++i) {
    if (i >= header_.size()) Fail("missing column '" + names[i] + "' in header");
    if (header_[i] != names[i]) {
      Fail("header column " + std::to_string(i + 1) + " is '" + header_[i] +
           "', expected '" + names[i] + "'");
    }
  }
}

bool CsvReader::NextRow(std::vector<std::string>* fields) {
  std::string raw;
  while (std::getline(in_, raw)) {
    ++line_;
    std::string s = TrimBlanks(raw);
    if (s.empty()) continue;
    if (s[0] == '#') Fail("metadata line after the header");
    *fields = SplitCsvLine(s);
    if (fields->size() != header_.size()) {
      Fail("row has " + std::to_string(fields->size()) + " fields, header has " +
           std::to_string(header_.size()) + " (truncated line?)");
    }
    return true;
  }
  return false;
}

double CsvReader::Double(const std::vector<std::string>& f, int col,
                         const char* name) const {
  const std::string& s = f[col];
  if (s.empty()) Fail(std::string("empty value in column '") + name + "'");
  errno = 0;
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) {
    Fail(std::string("'") + s + "' in column '" + name + "' is not a number");
  }
  if (!std::isfinite(v)) Fail(std::string("non-finite value in column '") + name + "'");
  return v;
}

int CsvReader::Int(const std::vector<std::string>& f, int col,
                   const char* name) const {
  const std::string& s = f[col];
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE ||
      v < -2147483647L || v > 2147483647L) {
    Fail(std::string("'") + s + "' in column '" + name + "' is not an integer");
  }
  return static_cast<int>(v);
}

}  // namespace hapcine
