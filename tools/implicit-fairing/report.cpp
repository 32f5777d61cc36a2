// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "report.h"

#include "common.h"

#include <nlohmann/json.hpp>

#include <cstdarg>
#include <cstdio>
#include <vector>

namespace implicit_fairing {
namespace {

std::string printfString(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string printfString(const char* format, ...)
{
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::vector<char> buf(static_cast<std::size_t>(n > 0 ? n : 0) + 1);
    std::vsnprintf(buf.data(), buf.size(), format, again);
    va_end(again);
    return buf.data();
}

}  // namespace

std::string jsonReport(const RunFacts& f)
{
    const fairing::Options& o = f.options;
    const fairing::Result& r = f.result;
    nlohmann::ordered_json j;  // keys in this order, as documented
    j["vertices"] = f.vertices;
    j["faces"] = f.faces;
    j["operator"] = f.cl.operatorName;
    j["order"] = o.order;
    j["integration"] = o.integration == fairing::Integration::Implicit ? "implicit"
                       : o.normalized                                 ? "explicit-normalized"
                                                                      : "explicit";
    j["boundary"] = f.cl.boundary;
    j["steps"] = r.steps;
    j["time_step"] = r.time_step;
    j["boundary_time_step"] = r.boundary_time_step;
    j["automatic_time_step"] = r.automatic_time_step;
    j["noise_level"] = r.noise_level;
    j["noise_level_edges"] = r.noise_level_edges;
    j["mean_edge_length"] = r.mean_edge_length;
    j["strength_seconds"] = r.strength_seconds;
    j["strength_iterations"] = r.strength_iterations;
    j["operator_frozen"] = r.operator_frozen;
    const nlohmann::json none;  // null: the risks were not compared
    j["recomputed_risk"] = r.operator_compared ? nlohmann::json(r.recomputed_risk) : none;
    j["frozen_risk"] = r.operator_compared ? nlohmann::json(r.frozen_risk) : none;
    j["frozen_risk_is_bound"] = r.operator_compared ? nlohmann::json(r.frozen_risk_is_bound) : none;
    j["lambda_dt"] = r.lambda_dt;
    j["cg_iterations"] = r.total_iterations;
    j["inner_iterations"] = r.total_inner_iterations;
    j["residual"] = r.max_residual;
    j["volume_before"] = r.volume_before;
    j["volume_after"] = r.volume_after;
    j["volume_restoration"] = nlohmann::json::array();  // per component, how it was restored
    for (const fairing::ComponentReport& c : r.components)
        j["volume_restoration"].push_back(fairing::to_string(c.restoration));
    j["vertices_moved"] = r.vertices_moved;
    j["vertices_fixed"] = r.vertices_fixed;
    j["merged_vertices"] = f.loaded.merged;
    j["components"] = r.components.size();
    j["boundary_loops"] = r.boundary_loops;
    j["seconds_engine"] = r.seconds;
    j["seconds_total"] = f.secondsTotal;
    j["warnings"] = r.warnings;
    // indent -1: one line; invalid UTF-8 (none expected) replaced rather than thrown
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string summaryLine(const RunFacts& f)
{
    const fairing::Result& r = f.result;
    const std::string volume = r.volume_before != 0  // 0: no closed component
                                   ? "volume " + formatNumber(r.volume_before) + " -> " +
                                         formatNumber(r.volume_after) + "; "
                                   : "";
    // The estimated risks of both (Result::recomputed_risk), the one taken first.
    const bool frozen = r.operator_frozen;
    const std::string operator_choice =
        r.operator_compared
            ? printfString("; %s operator: risk %.3g against %s%.3g %s",
                           frozen ? "frozen" : "recomputed",
                           frozen ? r.frozen_risk : r.recomputed_risk,
                           r.frozen_risk_is_bound ? "at least " : "",
                           frozen ? r.recomputed_risk : r.frozen_risk,
                           frozen ? "recomputed" : "frozen")
            : std::string();
    const std::string automatic =
        r.automatic_time_step
            ? printfString(" (automatic: noise %.3g edges%s)", r.noise_level_edges,
                           operator_choice.c_str())
            : std::string();
    return printfString(
        "%s: %s: %ld vertices (%d moved), %ld faces; %s, order %d, %d step%s, time step %g%s, "
        "lambda_dt %g; %d CG iterations, residual %.3g; %s%.6g s (engine %.6g s)",
        kTool, f.cl.out.c_str(), f.vertices, r.vertices_moved, f.faces,
        f.cl.operatorName.c_str(), f.options.order, r.steps, r.steps == 1 ? "" : "s",
        r.time_step, automatic.c_str(), r.lambda_dt, r.total_iterations, r.max_residual, volume.c_str(), f.secondsTotal,
        r.seconds);
}

}  // namespace implicit_fairing
