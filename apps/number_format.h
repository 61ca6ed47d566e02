// apps/number_format.h — numbers as the commands write them into CSV, JSON and tables: a value
// that is not finite (a measure not taken) is an empty field in CSV and text, null in JSON.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace footprint {

inline std::string format_number(double v, const char* format = "%.6g") {
    if (!std::isfinite(v)) return "";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}

inline nlohmann::json json_number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

}  // namespace footprint
