// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The only place where the MeshLab plugin APIs differ.
//
// The filter logic (filter_implicit_fairing.{h,cpp}) derives from fairing_plugin::FilterBase and
// implements the API-neutral hooks declared below; this header maps them onto
//   FAIRING_MESHLAB_API == 2020: MeshLab <= 2020.09, MeshFilterInterface (common/interfaces.h)
//   FAIRING_MESHLAB_API == 2025: MeshLab 2021.05 ... 2025.07, FilterPlugin
//                                (common/plugins/interfaces/filter_plugin.h)
// CMake sets FAIRING_MESHLAB_API (moc ignores __has_include, so it cannot be detected here).
//
// Differences handled here: base class, IID and Q_INTERFACES name, method signatures
// (QAction* vs const QAction*, const-ness, applyFilter's return type), error mapping
// (errorMessage + false vs MLException), Log vs log, UpdateBoxAndNormals vs
// updateBoxAndNormals, python names and the output map of a run's figures (new API only).
#pragma once

#include <fairing_parameters/repair_hints.h>

#include <QAction>
#include <QObject>
#include <QString>

#include <exception>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>

#if !defined(FAIRING_MESHLAB_API)
#error "FAIRING_MESHLAB_API must be defined (2020 or 2025) by the build system"
#endif

#if FAIRING_MESHLAB_API == 2020
#include <common/interfaces.h>
#define FAIRING_FILTER_IID MESH_FILTER_INTERFACE_IID
#define FAIRING_FILTER_INTERFACE MeshFilterInterface
#elif FAIRING_MESHLAB_API == 2025
#include <common/plugins/interfaces/filter_plugin.h>
#include <common/mlexception.h>
#define FAIRING_FILTER_IID FILTER_PLUGIN_IID
#define FAIRING_FILTER_INTERFACE FilterPlugin
#else
#error "FAIRING_MESHLAB_API must be 2020 or 2025"
#endif

namespace fairing_plugin {

using FilterId = int;   // FilterIDType (2020) and ActionIDType (2025) are both int

// What one run did, returned by apply(): integer counts and real values by name. The 2025 shim
// returns them as applyFilter's output map (pymeshlab hands it to Python as a dict, ints as int,
// values as float, flags as bool: pymeshlab's toPyDict converts no strings); the 2020 API has no
// output map and ignores them.
struct RunFigures {
    std::map<std::string, int> counts;
    std::map<std::string, double> values;
    std::map<std::string, bool> flags;
};

// The host whose words the error messages use (filter_parameters::render). A plugin cannot ask
// whether pymeshlab or the GUI loaded it, but its precision tells: pymeshlab 2025.7 is built in
// double and the MeshLab 2025.07 GUI in float, and each refuses a plugin of the other precision
// (PluginManager::checkPlugin), so the double binary runs only under pymeshlab.
#if FAIRING_MESHLAB_API == 2020
constexpr filter_parameters::Host kMessageHost = filter_parameters::Host::MeshLab2020;
#else
constexpr filter_parameters::Host kMessageHost = std::is_same<Scalarm, double>::value
                                                     ? filter_parameters::Host::Pymeshlab
                                                     : filter_parameters::Host::MeshLab2025;
#endif

class FilterBase : public QObject, public FAIRING_FILTER_INTERFACE {
public:
    using Interface = FAIRING_FILTER_INTERFACE;

    // ---- API-neutral hooks implemented by the filter logic --------------------------------
    // (filterName(FilterId) const, filterInfo(FilterId) const and pluginName() const have the
    // same signature in both APIs and are implemented directly.)
    virtual FilterClass classOf(FilterId id) const = 0;
    virtual int preConditionsOf(FilterId id) const = 0;
    virtual int postConditionOf(FilterId id) const = 0;
    virtual QString pythonNameOf(FilterId id) const = 0;
    // current: the current mesh or nullptr.
    virtual void initParameters(FilterId id, const MeshModel* current, RichParameterList& par) = 0;
    // Throws std::exception (fairing::Error) on failure; must leave the mesh untouched then.
    virtual RunFigures apply(FilterId id, MeshModel& m, const RichParameterList& par,
                             vcg::CallBackPos* cb) = 0;

protected:
    void registerFilters(std::initializer_list<FilterId> ids)
    {
        for (FilterId id : ids) typeList.push_back(id);
        for (FilterId id : ids) actionList.push_back(new QAction(filterName(id), this));
    }
    void logLine(const QString& line) { logLineImpl(line.toStdString()); }
    static void updateBoxAndNormals(MeshModel& m)
    {
#if FAIRING_MESHLAB_API == 2020
        m.UpdateBoxAndNormals();
#else
        m.updateBoxAndNormals();
#endif
    }

    // ---- the API-specific part ----------------------------------------------------------------
#if FAIRING_MESHLAB_API == 2020
public:
    FilterClass getClass(QAction* a) override { return classOf(ID(a)); }
    int getPreConditions(QAction* a) const override { return preConditionsOf(ID(a)); }
    int postCondition(QAction* a) const override { return postConditionOf(ID(a)); }
    FILTER_ARITY filterArity(QAction*) const override { return SINGLE_MESH; }
    void initParameterSet(QAction* a, MeshDocument& md, RichParameterList& par) override
    {
        initParameters(ID(a), md.mm(), par);
    }
    // The old API must never throw: meshlabserver aborts and the GUI hangs.
    bool applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                     vcg::CallBackPos* cb) override
    {
        errorMessage.clear();
        try {
            MeshModel* m = md.mm();
            if (m == nullptr) throw std::runtime_error("no current mesh");
            apply(ID(a), *m, par, cb);   // no output map in this API: the figures are in the log
            return true;
        } catch (const std::exception& e) {
            errorMessage = QString::fromUtf8(e.what());
        } catch (...) {
            errorMessage = QStringLiteral("unknown internal error");
        }
        // meshlabserver does not print errorMessage: put it in the log and on stderr too.
        logLineImpl("ERROR: " + errorMessage.toStdString());
        qWarning("%s failed: %s", qUtf8Printable(a->text()), qUtf8Printable(errorMessage));
        return false;
    }

private:
    void logLineImpl(const std::string& s) { Log(s); }
#else  // 2025
public:
    QString pythonFilterName(ActionIDType id) const override { return pythonNameOf(id); }
    FilterClass getClass(const QAction* a) const override { return classOf(ID(a)); }
    int getPreConditions(const QAction* a) const override { return preConditionsOf(ID(a)); }
    int postCondition(const QAction* a) const override { return postConditionOf(ID(a)); }
    FilterArity filterArity(const QAction*) const override { return SINGLE_MESH; }
    RichParameterList initParameterList(const QAction* a, const MeshDocument& md) override
    {
        RichParameterList par;
        initParameters(ID(a), md.mm(), par);
        return par;
    }
    // Errors reach the host as MLException (pymeshlab raises PyMeshLabException with its text);
    // the figures of the run come back as the output map (a dict in pymeshlab).
    std::map<std::string, QVariant> applyFilter(const QAction* a, const RichParameterList& par,
                                                MeshDocument& md, unsigned int& postConditionMask,
                                                vcg::CallBackPos* cb) override
    {
        MeshModel* m = md.mm();
        if (m == nullptr) throw MLException("no current mesh");
        RunFigures figures;
        try {
            figures = apply(ID(a), *m, par, cb);
        } catch (const MLException&) {
            throw;
        } catch (const std::exception& e) {
            throw MLException(QString::fromUtf8(e.what()));
        } catch (...) {
            throw MLException(QStringLiteral("unknown internal error"));
        }
        postConditionMask = static_cast<unsigned int>(postConditionOf(ID(a)));
        std::map<std::string, QVariant> out;
        for (const auto& c : figures.counts) out[c.first] = QVariant(c.second);
        for (const auto& v : figures.values) out[v.first] = QVariant(v.second);
        for (const auto& f : figures.flags) out[f.first] = QVariant(f.second);
        return out;
    }

private:
    void logLineImpl(const std::string& s) { log(s); }
#endif
};

}  // namespace fairing_plugin
