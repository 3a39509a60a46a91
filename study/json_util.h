#pragma once
// Checked access to the study's JSON files: a missing or mistyped field is a
// one-line hapcine::Error naming the file and the field, never an exception
// from deep inside nlohmann::json.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace hapcine::study {

// Parses a whole file; Error(path, "not valid JSON: ...") on failure.
nlohmann::json ReadJsonFile(const std::string& path);

const nlohmann::json& Field(const nlohmann::json& j, const std::string& key,
                            const std::string& source, const std::string& where);
std::string StringField(const nlohmann::json& j, const std::string& key, const std::string& source,
                        const std::string& where);
double NumberField(const nlohmann::json& j, const std::string& key, const std::string& source,
                   const std::string& where);
int IntField(const nlohmann::json& j, const std::string& key, const std::string& source,
             const std::string& where);
uint64_t Uint64Field(const nlohmann::json& j, const std::string& key, const std::string& source,
                     const std::string& where);
const nlohmann::json& ArrayField(const nlohmann::json& j, const std::string& key,
                                 const std::string& source, const std::string& where);
std::vector<std::string> StringArray(const nlohmann::json& j, const std::string& source,
                                     const std::string& where);

// Current UTC time as ISO 8601 ("2026-11-22T07:30:00Z").
std::string UtcNow();

}  // namespace hapcine::study
