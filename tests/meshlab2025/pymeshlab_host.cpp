// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// A pymeshlab-like host for the MeshLab 2025.07 integration tests: everything pymeshlab 2025.7
// does to run a plugin's filter, except its pybind11 layer. No Python, no display, no GL.
//
//   pymeshlab_host PLUGINS_DIR PLUGIN COMMAND ...
//
// PLUGINS_DIR is loaded first (the SDK's io_base, as pymeshlab loads its lib/plugins), then
// PLUGIN the way pymeshlab.load_plugin(path) does: PluginManager::checkPlugin, loadPlugin, and
// FunctionSet::loadFilterPlugin on pymeshlab::functionSetInstance().
//
//   list
//       every filter of PLUGIN: python name, then one line per parameter
//       (the deprecated aliases MeshLab 2022.02's function set adds: "deprecated <name>" lines)
//       "param <python name> <python type> <meshlab name> default=<value>", followed for an
//       enum by "labels <python name> <label>|<label>|..." (the strings pymeshlab accepts)
//   apply IN.ply OUT.ply PYTHON_FILTER_NAME [--select-x-gt V] [--params-out FILE]
//         [--expect-failure] [python_name=value ...]
//       MeshSet.load_new_mesh(IN), MeshSet.apply_filter(NAME, **kwargs), save_current_mesh(OUT).
//       Values are converted as pymeshlab converts keyword arguments: bool (True/False/true/
//       false/1/0), int, float (through a C float, as pymeshlab's py::cast<float>), enum (label
//       string or index). --select-x-gt selects the vertices with x > V before the filter (what
//       compute_selection_by_condition_per_vertex(condselect='x > V') does; that plugin is not
//       in the SDK). --params-out writes the parameter list the filter received, one
//       "internalName=value" per line (the input of engine_reference). The output map is
//       printed as "output <key> <int|double|...> <value>" lines.
//       --expect-failure: the filter must throw; the host prints the message pymeshlab raises,
//       checks that the mesh is unchanged and that nothing is returned, and saves nothing.
//   reject OTHER_PLUGIN
//       OTHER_PLUGIN must be refused (checkPlugin and loadPlugin throw MLException); prints
//       "rejected: <message>".
// Exit status 0 on success, 1 on a failed check, 2 on a usage error.
#include <common/globals.h>
#include <common/mlexception.h>
#include <common/parameters/rich_parameter_list.h>
#include <common/plugins/interfaces/filter_plugin.h>
#include <common/plugins/meshlab_plugin_type.h>
#include <common/plugins/plugin_manager.h>
#include <common/python/function.h>
#include <common/python/function_parameter.h>
#include <common/python/function_set.h>
#include <common/python/python_utils.h>
#include <common/utilities/load_save.h>

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTextStream>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

[[noreturn]] void usage(const std::string& msg)
{
    std::fprintf(stderr, "pymeshlab_host: %s\n", msg.c_str());
    std::exit(2);
}

[[noreturn]] void fail(const std::string& msg)
{
    std::printf("FAIL: %s\n", msg.c_str());
    std::fflush(stdout);
    std::exit(1);
}

QString absolute(const QString& f) { return QFileInfo(f).absoluteFilePath(); }

// pymeshlab.load_plugin(path) (PyMeshLab's module_functions.cpp, pymeshlab::loadPlugin).
FilterPlugin* loadPluginLikePymeshlab(const QString& path)
{
    MeshLabPluginType type = PluginManager::checkPlugin(path);
    if (!(type.isIOPlugin() || type.isFilterPlugin()))
        throw MLException("Error while loading plugin: PyMeshLab only supports IO or Filter plugins.");
    PluginManager& pm = meshlab::pluginManagerInstance();
    pymeshlab::FunctionSet& fs = pymeshlab::functionSetInstance();
    MeshLabPlugin* p = pm.loadPlugin(path);
    FilterPlugin* fp = dynamic_cast<FilterPlugin*>(p);
    if (fp == nullptr) fail("the plugin is not a filter plugin");
    fs.loadFilterPlugin(fp);
    return fp;
}

bool parseBool(const std::string& v, const std::string& name)
{
    if (v == "True" || v == "true" || v == "1") return true;
    if (v == "False" || v == "false" || v == "0") return false;
    throw MLException(QString::fromStdString("Parameter " + name + ": not a bool: " + v));
}

bool isInteger(const std::string& v)
{
    if (v.empty()) return false;
    std::size_t i = (v[0] == '-' || v[0] == '+') ? 1 : 0;
    if (i == v.size()) return false;
    for (; i < v.size(); ++i)
        if (v[i] < '0' || v[i] > '9') return false;
    return true;
}

// One keyword argument, converted the way pymeshlab's updateRichParameterFromKwarg does for
// the types this plugin uses (bool, int, float, enum).
void setFromKwarg(RichParameter& par, const std::string& pyName, const std::string& v)
{
    if (par.isOfType<RichBool>()) {
        par.setValue(BoolValue(parseBool(v, pyName)));
    }
    else if (par.isOfType<RichEnum>()) {
        const RichEnum& en = dynamic_cast<const RichEnum&>(par);
        int value;
        if (isInteger(v)) {
            value = std::stoi(v);
            if (!(value >= 0 && value < en.enumvalues.size()))
                throw MLException(QString("Enum %1 not valid. Must be a value between 0 and %2")
                                      .arg(value).arg(en.enumvalues.size()));
        }
        else {
            value = en.enumvalues.indexOf(QString::fromStdString(v));
            if (value == -1) {
                QString list;
                for (const QString& s : en.enumvalues) list += "'" + s + "'; ";
                throw MLException("Enum '" + QString::fromStdString(v) +
                                  "' not found. Possible values are " + list);
            }
        }
        par.setValue(IntValue(value));
    }
    else if (par.isOfType<RichInt>()) {
        if (!isInteger(v)) throw MLException(QString::fromStdString("Parameter " + pyName + ": not an int: " + v));
        par.setValue(IntValue(std::stoi(v)));
    }
    else if (par.isOfType<RichFloat>()) {
        // pymeshlab: FloatValue(py::cast<float>(value))
        par.setValue(FloatValue(std::stof(v)));
    }
    else {
        fail("parameter " + pyName + " has a type this host does not emulate: " +
             par.stringType().toStdString());
    }
}

std::string valueString(const RichParameter& par)
{
    const Value& v = par.value();
    if (par.isOfType<RichBool>()) return v.getBool() ? "true" : "false";
    if (par.isOfType<RichEnum>() || par.isOfType<RichInt>()) return std::to_string(v.getInt());
    if (par.isOfType<RichFloat>()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v.getFloat()));
        return buf;
    }
    return "?";
}

std::string variantString(const QVariant& q)
{
    return std::string(q.typeName()) + " " + q.toString().toStdString();
}

// MeshSet.apply_filter(name, **kwargs) (PyMeshLab's MeshSet::applyFilter and
// meshsethelper::applyFilterRPL): returns the output map, throws MLException with pymeshlab's
// message on failure.
std::map<std::string, QVariant> applyFilterLikePymeshlab(
    MeshDocument& md, const std::string& pythonName,
    const std::vector<std::pair<std::string, std::string>>& kwargs, const QString& paramsOut)
{
    const QString name = QString::fromStdString(pythonName);
    pymeshlab::FunctionSet& fs = pymeshlab::functionSetInstance();
    if (!fs.containsFilterFunction(name))
        throw MLException("Failed to apply filter: " + name + "\n" +
                          "Filter does not exists. Take a look at MeshSet.print_filter_list function.");
    const pymeshlab::Function& f = fs.filterFunction(name);
    PluginManager& pm = meshlab::pluginManagerInstance();
    QAction* action = pm.filterAction(f.meshlabFunctionName());
    FilterPlugin* fp = action == nullptr ? nullptr : pm.getFilterPluginFromAction(action);
    if (fp == nullptr) fail("no plugin for " + f.meshlabFunctionName().toStdString());

    RichParameterList rpl = fp->initParameterList(action, md);
    for (const auto& kw : kwargs) {
        const QString key = QString::fromStdString(kw.first);
        if (!f.contains(key))
            throw MLException("Parameter " + key + " not found for filter " +
                              f.pythonFunctionName() + ". Please check the documentation.");
        const pymeshlab::FunctionParameter& ffp = f.getFilterFunctionParameter(key);
        auto it = rpl.findParameter(ffp.meshlabName());
        if (it == rpl.end()) fail("parameter " + kw.first + " missing from the filter's list");
        setFromKwarg(*it, kw.first, kw.second);
    }
    if (!paramsOut.isEmpty()) {
        QFile out(paramsOut);
        if (!out.open(QIODevice::WriteOnly | QIODevice::Text)) usage("cannot write " + paramsOut.toStdString());
        QTextStream ts(&out);
        for (const RichParameter& p : rpl)
            ts << p.name() << "=" << QString::fromStdString(valueString(p)) << "\n";
    }

    QStringList missing;
    if (!fp->isFilterApplicable(action, *md.mm(), missing))
        throw MLException("Failed to apply filter:  '" + name + ". Current mesh does not have " +
                          missing.join(",") + ".");
    fp->setLog(&md.Log);
    try {
        md.mm()->updateDataMask(fp->getRequirements(action));
        md.meshDocStateData().clear();
        md.meshDocStateData().create(md);
        md.setBusy(true);
        unsigned int postConditionMask = MeshModel::MM_UNKNOWN;
        std::map<std::string, QVariant> out =
            fp->applyFilter(action, rpl, md, postConditionMask, nullptr);
        md.setBusy(false);
        for (MeshModel& mm : md.meshIterator()) vcg::tri::Allocator<CMeshO>::CompactEveryVector(mm.cm);
        fp->setLog(nullptr);
        return out;
    }
    catch (const std::exception& e) {
        md.setBusy(false);
        fp->setLog(nullptr);
        throw MLException("Failed to apply filter: " + name + "\n" + "Details: " + e.what());
    }
}

// MeshSet.save_current_mesh(file) with default arguments (PyMeshLab's
// meshsethelper::saveMeshUsingPlugin): what the mesh has, of what the format saves by default.
void saveLikePymeshlab(const QString& file, MeshModel& mm)
{
    const QString ext = QFileInfo(file).suffix().toLower();
    IOPlugin* plugin = meshlab::pluginManagerInstance().outputMeshPlugin(ext);
    if (plugin == nullptr) throw MLException("Unknown format for save: " + ext);
    int capabilityFormat = 0, defaultSaveSettings = 0, capabilityMesh = 0;
    plugin->exportMaskCapability(ext, capabilityFormat, defaultSaveSettings);
    for (int bit : pymeshlab::capabilitiesBits)
        if (mm.hasDataMask(MeshModel::io2mm(bit))) capabilityMesh |= bit;
    capabilityMesh &= capabilityFormat;
    defaultSaveSettings &= capabilityMesh;
    RichParameterList rps = plugin->initSaveParameter(ext, mm);
    plugin->save(ext, file, mm, defaultSaveSettings, rps, nullptr);
}

std::vector<Point3m> positions(const CMeshO& m)
{
    std::vector<Point3m> p;
    for (const auto& v : m.vert) p.push_back(v.cP());
    return p;
}

int cmdList()
{
    pymeshlab::FunctionSet& fs = pymeshlab::functionSetInstance();
    int n = 0;
    for (const pymeshlab::Function& f : fs.filterFunctionIterator()) {
        if (!f.meshlabFunctionName().startsWith("Implicit Fairing")) continue;
        if (f.isDeprecated()) {   // 2022.02 adds the old, menu-text-derived name of each filter
            std::printf("deprecated %s <- '%s'\n", qUtf8Printable(f.pythonFunctionName()),
                        qUtf8Printable(f.meshlabFunctionName()));
            continue;
        }
        ++n;
        std::printf("filter %s <- '%s'\n", qUtf8Printable(f.pythonFunctionName()),
                    qUtf8Printable(f.meshlabFunctionName()));
        for (const pymeshlab::FunctionParameter& p : f) {
            std::printf("param %s %s %s default=%s\n", qUtf8Printable(p.pythonName()),
                        qUtf8Printable(p.pythonTypeString().replace(' ', '_')),
                        qUtf8Printable(p.meshlabName()),
                        qUtf8Printable(p.defaultValueString()));
            if (p.richParameter().isOfType<RichEnum>())
                std::printf("labels %s %s\n", qUtf8Printable(p.pythonName()),
                            qUtf8Printable(dynamic_cast<const RichEnum&>(p.richParameter())
                                               .enumvalues.join('|')));
        }
    }
    if (n != 3) fail("expected 3 implicit fairing filters in the function set, found " + std::to_string(n));
    return 0;
}

int cmdApply(int argc, char** argv, int i)
{
    if (argc - i < 3) usage("apply IN.ply OUT.ply PYTHON_FILTER_NAME [options] [name=value ...]");
    const QString in = absolute(argv[i]), out = absolute(argv[i + 1]);
    const std::string filter = argv[i + 2];
    bool select = false, expectFailure = false;
    Scalarm selectX = 0;
    QString paramsOut;
    std::vector<std::pair<std::string, std::string>> kwargs;
    for (i += 3; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--select-x-gt" && i + 1 < argc) { select = true; selectX = std::stod(argv[++i]); }
        else if (a == "--params-out" && i + 1 < argc) paramsOut = absolute(argv[++i]);
        else if (a == "--expect-failure") expectFailure = true;
        else {
            const auto eq = a.find('=');
            if (eq == std::string::npos) usage("bad argument " + a);
            kwargs.emplace_back(a.substr(0, eq), a.substr(eq + 1));
        }
    }

    MeshDocument md;
    meshlab::loadMeshWithStandardParameters(in, md);   // MeshSet.load_new_mesh
    if (md.mm() == nullptr) fail("no mesh loaded from " + in.toStdString());
    std::printf("loaded %s: %d vertices, %d faces%s\n", qUtf8Printable(in), md.mm()->cm.vn,
                md.mm()->cm.fn,
                md.mm()->hasDataMask(MeshModel::MM_VERTQUALITY) ? ", vertex quality" : "");
    if (select) {
        int n = 0;
        for (auto& v : md.mm()->cm.vert)
            if (!v.IsD() && v.P()[0] > selectX) { v.SetS(); ++n; }
        std::printf("selected %d vertices with x > %g\n", n, static_cast<double>(selectX));
    }

    const std::vector<Point3m> before = positions(md.mm()->cm);
    std::map<std::string, QVariant> output;
    try {
        output = applyFilterLikePymeshlab(md, filter, kwargs, paramsOut);
    }
    catch (const MLException& e) {
        std::printf("PyMeshLabException: %s\n", e.what());
        if (!expectFailure) fail("the filter failed");
        if (positions(md.mm()->cm) != before) fail("the failed filter changed the mesh");
        std::printf("mesh unchanged after the failure (%zu vertices compared)\n", before.size());
        return 0;
    }
    if (expectFailure) fail("the filter did not fail");
    for (const auto& o : output)
        std::printf("output %s %s\n", o.first.c_str(), variantString(o.second).c_str());
    saveLikePymeshlab(out, *md.mm());
    std::printf("saved %s\n", qUtf8Printable(out));
    return 0;
}

// true if what() threw MLException (printed after prefix)
template <typename F>
bool refuses(const char* prefix, F what)
{
    try {
        what();
    }
    catch (const MLException& e) {
        std::printf("%s%s\n", prefix, e.what());
        return true;
    }
    return false;
}

int cmdReject(const QString& other)
{
    const bool checked = refuses("rejected: ", [&] { PluginManager::checkPlugin(other); });
    const bool loaded = refuses("load_plugin: PyMeshLabException: ",
                                [&] { loadPluginLikePymeshlab(other); });
    if (!checked || !loaded) fail("the plugin of the other precision was not refused");
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    QCoreApplication app(argc, argv);
    if (argc < 4) usage("usage: PLUGINS_DIR PLUGIN list|apply|reject ...");
    const QString pluginsDir = absolute(argv[1]), plugin = absolute(argv[2]);
    const std::string cmd = argv[3];
    std::printf("host: MeshLab %s, %s precision\n", meshlab::meshlabVersion().c_str(),
                meshlab::builtWithDoublePrecision() ? "double" : "float");
    try {
        PluginManager& pm = meshlab::pluginManagerInstance();
        pm.loadPlugins(QDir(pluginsDir));   // pymeshlab loads its lib/plugins the same way
        if (pm.outputMeshPlugin("ply") == nullptr) fail("io_base not loaded from " + pluginsDir.toStdString());
        if (cmd == "reject") {
            if (argc < 5) usage("reject OTHER_PLUGIN");
            return cmdReject(absolute(argv[4]));
        }
        FilterPlugin* fp = loadPluginLikePymeshlab(plugin);
        std::printf("loaded plugin %s (%s)\n", qUtf8Printable(fp->pluginName()), qUtf8Printable(plugin));
        if (cmd == "list") return cmdList();
        if (cmd == "apply") return cmdApply(argc, argv, 4);
        usage("unknown command " + cmd);
    }
    catch (const MLException& e) {
        fail(std::string("MLException: ") + e.what());
    }
    catch (const std::exception& e) {
        fail(std::string("exception: ") + e.what());
    }
}
