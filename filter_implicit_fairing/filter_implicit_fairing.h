// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// MeshLab filter plugin: implicit fairing of irregular meshes (Desbrun, Meyer, Schroeder, Barr,
// SIGGRAPH 1999). Three filters, one per operator of the paper, in
// Filters > Smoothing, Fairing and Deformation. The filter logic here is API-neutral; the
// MeshLab API (2020.09 MeshFilterInterface or 2025.07 FilterPlugin) is mapped in meshlab_api.h.
#pragma once

#include "meshlab_api.h"

#include <fairing/fairing.h>
#include <fairing_parameters/filter_parameters.h>
#include <vcg_adapters/vcg_adapters.h>

class FilterImplicitFairing : public fairing_plugin::FilterBase {
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(FAIRING_FILTER_IID)
    Q_INTERFACES(FAIRING_FILTER_INTERFACE)

public:
    enum { FP_UMBRELLA, FP_SCALE_DEPENDENT, FP_CURVATURE_FLOW };

    FilterImplicitFairing();

    QString pluginName() const override;
    QString filterName(fairing_plugin::FilterId id) const override;
    QString filterInfo(fairing_plugin::FilterId id) const override;

    FilterClass classOf(fairing_plugin::FilterId id) const override;
    int preConditionsOf(fairing_plugin::FilterId id) const override;
    int postConditionOf(fairing_plugin::FilterId id) const override;
    QString pythonNameOf(fairing_plugin::FilterId id) const override;
    void initParameters(fairing_plugin::FilterId id, const MeshModel* current,
                        RichParameterList& par) override;
    fairing_plugin::RunFigures apply(fairing_plugin::FilterId id, MeshModel& m,
                                     const RichParameterList& par,
                                     vcg::CallBackPos* cb) override;

private:
    // apply() without rendering fairing::Error for the host
    fairing_plugin::RunFigures run(fairing_plugin::FilterId id, MeshModel& m,
                                   const RichParameterList& par, vcg::CallBackPos* cb);
    void logRun(fairing_plugin::FilterId id, const filter_parameters::Values& v,
                const fairing::Options& o, const vcg_adapters::ConstraintSettings& cs,
                const vcg_adapters::ConstraintReport& crep, const fairing::Result& r,
                long vertices, double seconds);
    void logSolves(const fairing::Result& r);
    void logComponents(const fairing::Options& o, const fairing::Result& r);
    void logWarnings(const fairing::Result& r);
};
