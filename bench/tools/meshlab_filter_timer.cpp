// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// meshlab_filter_timer: times ONE MeshLab 2020.09 filter in-process, as meshlabserver runs it but
// without its start-up, X server, mesh loading and saving in the measurement.
//
//   meshlab_filter_timer PLUGIN.so "FILTER NAME" IN.ply OUT.ply [name=value ...] [--repeat N]
//                        [--io IO_PLUGIN.so] [--checkpoints K1,K2,...]
//
// - IN is imported with Debian's own io_base plugin (libio_base.so next to PLUGIN.so's
//   siblings in /usr/lib/x86_64-linux-gnu/meshlab/plugins, or --io) and prepared exactly as
//   meshlabserver's MeshLabServer::importMesh does (src/meshlabserver/mainserver.cpp:
//   UpdateBoxAndNormals, MM_VERTNORMAL, the polygonal branch); then, as MeshLabServer::script
//   does before applyFilter: updateDataMask(getRequirements), the selection counts svn/sfn.
//   meshlabserver also creates a GL context for every filter; this tool does not (none of the
//   smoothing filters uses it), so it runs with QT_QPA_PLATFORM=offscreen and no X server.
// - FILTER NAME is the action text (what .mlx files carry in <filter name=...>). The parameters
//   are the filter's defaults (initParameterSet on the loaded document, as meshlabserver fills
//   the ones a script leaves out) overridden by name=value, parsed as MeshLab parses .mlx values
//   (int, float, absolute/percentage as float, enum as its index, bool: anything but "false").
// - Only applyFilter is timed (std::chrono::steady_clock), --repeat N times (default 1), each
//   time on a freshly imported mesh; the median is reported. The last result is written to OUT
//   with io_base, binary, attribute mask 0 (coordinates and faces), as meshlabserver -o does.
// - The filter's log (GLLogStream) goes to stderr; when it carries "Time: X s in the engine"
//   (the implicit fairing plugin) the JSON also has engine_seconds (median) and overhead =
//   (seconds - engine_seconds) / engine_seconds.
//
// - --checkpoints K1,K2,... (increasing; for the denoising study, bench/denoise.sh): applies the
//   filter Kn times in a row to the same mesh, as a user clicking Apply again would, and writes
//   the mesh after the Ki-th application to OUT with "_cKi" before its extension (OUT itself is
//   not written); "seconds" is then the total applyFilter time of all applications and the JSON
//   has "checkpoints": [[Ki, seconds so far], ...]. --repeat is ignored.
//
// stdout: one JSON line {"filter", "vertices", "faces", "seconds", "all", ["engine_seconds",
// "engine_all", "overhead", "cg_iterations"]}. Exit status 1 when the filter fails.
#include <common/GLLogStream.h>
#include <common/interfaces.h>
#include <common/meshmodel.h>

#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <QPluginLoader>
#include <QRegularExpression>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

const char* kDefaultIo = "/usr/lib/x86_64-linux-gnu/meshlab/plugins/libio_base.so";

int usage()
{
    std::fprintf(stderr, "usage: meshlab_filter_timer PLUGIN.so \"FILTER NAME\" IN.ply OUT.ply "
                         "[name=value ...] [--repeat N] [--io IO_PLUGIN.so]\n");
    return 2;
}

template <class T>
T* loadPlugin(const QString& path, QPluginLoader& loader)
{
    loader.setFileName(path);
    QObject* instance = loader.instance();
    if (instance == nullptr) {
        std::fprintf(stderr, "cannot load %s: %s\n", qUtf8Printable(path),
                     qUtf8Printable(loader.errorString()));
        return nullptr;
    }
    T* p = qobject_cast<T*>(instance);
    if (p == nullptr) std::fprintf(stderr, "%s: not the expected plugin type\n", qUtf8Printable(path));
    return p;
}

// MeshLabServer::importMesh (mainserver.cpp), without the GL shared context.
bool importMesh(MeshIOInterface& io, MeshDocument& md, MeshModel& mm, const QString& fileName)
{
    const QFileInfo fi(fileName);
    const QDir curDir = QDir::current();
    QDir::setCurrent(fi.absolutePath());
    const QString extension = fi.suffix();
    int mask = 0;
    RichParameterList prePar;
    io.initPreOpenParameter(extension, fileName, prePar);
    io.setLog(&md.Log);
    if (!io.open(extension, fileName, mm, mask, prePar)) {
        std::fprintf(stderr, "failed loading %s: %s\n", qUtf8Printable(fileName),
                     qUtf8Printable(io.errorMsg()));
        QDir::setCurrent(curDir.absolutePath());
        return false;
    }
    if (mask & vcg::tri::io::Mask::IOM_BITPOLYGONAL) {
        mm.updateDataMask(MeshModel::MM_POLYGONAL);
        vcg::tri::Clean<CMeshO>::RemoveDegenerateFace(mm.cm);
        mm.updateDataMask(MeshModel::MM_FACEFACETOPO);
        vcg::tri::UpdateNormal<CMeshO>::PerBitQuadFaceNormalized(mm.cm);
        vcg::tri::UpdateNormal<CMeshO>::PerVertexFromCurrentFaceNormal(mm.cm);
    } else if (mask & vcg::tri::io::Mask::IOM_VERTNORMAL) {
        vcg::tri::UpdateNormal<CMeshO>::PerFace(mm.cm);
        vcg::tri::UpdateBounding<CMeshO>::Box(mm.cm);
    } else {
        mm.UpdateBoxAndNormals();
    }
    if (mm.cm.fn == 0) {
        if (mask & vcg::tri::io::Mask::IOM_VERTNORMAL) mm.updateDataMask(MeshModel::MM_VERTNORMAL);
    } else {
        mm.updateDataMask(MeshModel::MM_VERTNORMAL);
    }
    QDir::setCurrent(curDir.absolutePath());
    return true;
}

// MeshLabServer::exportMesh with meshlabserver -o's defaults: mask 0, binary.
bool exportMesh(MeshIOInterface& io, MeshModel& mm, const QString& fileName)
{
    const QFileInfo fi(fileName);
    const QDir curDir = QDir::current();
    QDir::setCurrent(fi.absolutePath());
    QString extension = fi.suffix();
    RichParameterList savePar;
    io.initSaveParameter(extension, mm, savePar);
    if (savePar.hasParameter("Binary")) savePar.setValue("Binary", BoolValue(true));
    int formatmask = 0, defbits = 0;
    io.GetExportMaskCapability(extension, formatmask, defbits);
    const bool ok = io.save(extension, fileName, mm, 0 & formatmask, savePar);
    QDir::setCurrent(curDir.absolutePath());
    if (!ok) std::fprintf(stderr, "failed saving %s\n", qUtf8Printable(fileName));
    return ok;
}

bool callback(const int, const char*)   // meshlabserver's filterCallBack prints; this one doesn't
{
    return true;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string jsonList(const std::vector<double>& v)
{
    std::string s = "[";
    char buf[32];
    for (size_t i = 0; i < v.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s%.6g", i ? "," : "", v[i]);
        s += buf;
    }
    return s + "]";
}

std::string jsonString(const QString& q)
{
    std::string s = "\"";
    for (char c : q.toStdString()) {
        if (c == '"' || c == '\\') s += '\\';
        s += c;
    }
    return s + "\"";
}

}  // namespace

int main(int argc, char** argv)
{
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);   // the plugins create QActions
    std::vector<QString> assignments;
    QString ioPath = kDefaultIo;
    int repeat = 1;
    std::vector<int> checkpoints;
    std::vector<QString> pos;
    for (int i = 1; i < argc; ++i) {
        const QString a = QString::fromLocal8Bit(argv[i]);
        if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
        else if (a == "--io" && i + 1 < argc) ioPath = QString::fromLocal8Bit(argv[++i]);
        else if (a == "--checkpoints" && i + 1 < argc) {
            for (const QString& k : QString::fromLocal8Bit(argv[++i]).split(','))
                if (k.toInt() > (checkpoints.empty() ? 0 : checkpoints.back())) checkpoints.push_back(k.toInt());
        }
        else if (pos.size() < 4) pos.push_back(a);
        else assignments.push_back(a);
    }
    if (pos.size() < 4) return usage();
    if (!checkpoints.empty()) repeat = 1;
    const QString pluginPath = pos[0], filterName = pos[1];
    const QString in = QFileInfo(pos[2]).absoluteFilePath(), out = QFileInfo(pos[3]).absoluteFilePath();

    QPluginLoader ioLoader, filterLoader;
    MeshIOInterface* io = loadPlugin<MeshIOInterface>(ioPath, ioLoader);
    MeshFilterInterface* filter = loadPlugin<MeshFilterInterface>(pluginPath, filterLoader);
    if (io == nullptr || filter == nullptr) return 1;
    QAction* action = nullptr;
    for (QAction* a : filter->actions())
        if (a->text() == filterName) action = a;
    if (action == nullptr) {
        std::fprintf(stderr, "no filter named '%s' in %s; it has:\n", qUtf8Printable(filterName),
                     qUtf8Printable(pluginPath));
        for (QAction* a : filter->actions()) std::fprintf(stderr, "  %s\n", qUtf8Printable(a->text()));
        return 2;
    }

    std::vector<double> seconds, engine;
    std::vector<std::pair<int, double>> reached;  // --checkpoints: (applications, seconds so far)
    long long cgIterations = -1;
    int vn = 0, fn = 0;
    const QRegularExpression engineRe("Time: ([0-9.eE+-]+) s in the engine");
    const QRegularExpression itsRe("CG iterations in total: (\\d+)");
    for (int run = 0; run < repeat; ++run) {
        MeshDocument md;
        MeshModel* mm = md.addNewMesh(in, "");
        if (mm == nullptr || !importMesh(*io, md, *mm, in)) return 1;
        vn = mm->cm.vn;
        fn = mm->cm.fn;

        // MeshLabServer::script, before applyFilter
        GLLogStream log;
        filter->setLog(&log);
        mm->updateDataMask(filter->getRequirements(action));
        RichParameterList par;
        filter->initParameterSet(action, md, par);
        for (const QString& kv : assignments) {
            const int eq = kv.indexOf('=');
            const QString name = kv.left(eq), value = kv.mid(eq + 1);
            if (eq < 0 || !par.hasParameter(name)) {
                std::fprintf(stderr, "unknown parameter '%s'; the filter has:", qUtf8Printable(kv));
                for (const RichParameter& p : par) std::fprintf(stderr, " %s", qUtf8Printable(p.name()));
                std::fprintf(stderr, "\n");
                return 2;
            }
            const Value& old = par.getParameterByName(name).value();
            bool ok = true;
            if (old.isEnum()) par.setValue(name, EnumValue(value.toInt(&ok)));
            else if (old.isAbsPerc()) par.setValue(name, AbsPercValue(value.toFloat(&ok)));
            else if (old.isBool()) par.setValue(name, BoolValue(value.toLower() != "false"));
            else if (old.isInt()) par.setValue(name, IntValue(value.toInt(&ok)));
            else if (old.isFloat()) par.setValue(name, FloatValue(value.toFloat(&ok)));
            else ok = false;
            if (!ok) {
                std::fprintf(stderr, "parameter '%s': unsupported type or bad value\n", qUtf8Printable(kv));
                return 2;
            }
        }
        mm->cm.svn = int(vcg::tri::UpdateSelection<CMeshO>::VertexCount(mm->cm));
        mm->cm.sfn = int(vcg::tri::UpdateSelection<CMeshO>::FaceCount(mm->cm));

        const int applications = checkpoints.empty() ? 1 : checkpoints.back();
        double total = 0;
        bool ok = true;
        for (int k = 1; k <= applications && ok; ++k) {
            md.setBusy(true);
            const auto t0 = std::chrono::steady_clock::now();
            ok = filter->applyFilter(action, md, par, callback);
            const auto t1 = std::chrono::steady_clock::now();
            md.setBusy(false);
            total += std::chrono::duration<double>(t1 - t0).count();
            if (ok && std::find(checkpoints.begin(), checkpoints.end(), k) != checkpoints.end()) {
                const QFileInfo fo(out);
                const QString name = fo.path() + "/" + fo.completeBaseName() + "_c" + QString::number(k) +
                                     "." + fo.suffix();
                if (!exportMesh(*io, *md.mm(), name)) return 1;
                reached.emplace_back(k, total);
            }
        }
        seconds.push_back(total);

        QStringList lines;
        log.print(lines);
        for (const QString& l : lines) {
            std::fprintf(stderr, "%s\n", qUtf8Printable(l));
            const auto m = engineRe.match(l);
            if (m.hasMatch()) engine.push_back(m.captured(1).toDouble());
            const auto c = itsRe.match(l);
            if (c.hasMatch()) cgIterations = c.captured(1).toLongLong();
        }
        if (!ok) {
            std::fprintf(stderr, "filter '%s' failed: %s\n", qUtf8Printable(filterName),
                         qUtf8Printable(filter->errorMsg()));
            return 1;
        }
        if (checkpoints.empty() && run + 1 == repeat && !exportMesh(*io, *md.mm(), out)) return 1;
    }

    const double s = median(seconds);
    std::string j = "{\"filter\":" + jsonString(filterName) + ",\"vertices\":" + std::to_string(vn) +
                    ",\"faces\":" + std::to_string(fn);
    char buf[64];
    std::snprintf(buf, sizeof buf, ",\"seconds\":%.6g", s);
    j += buf;
    j += ",\"all\":" + jsonList(seconds);
    if (engine.size() == seconds.size()) {
        const double e = median(engine);
        std::snprintf(buf, sizeof buf, ",\"engine_seconds\":%.6g", e);
        j += buf;
        j += ",\"engine_all\":" + jsonList(engine);
        std::vector<double> over;
        for (size_t i = 0; i < engine.size(); ++i)
            if (engine[i] > 0) over.push_back((seconds[i] - engine[i]) / engine[i]);
        if (!over.empty()) {
            std::snprintf(buf, sizeof buf, ",\"overhead\":%.6g", median(over));
            j += buf;
        }
    }
    if (cgIterations >= 0) j += ",\"cg_iterations\":" + std::to_string(cgIterations);
    if (!checkpoints.empty()) {
        j += ",\"checkpoints\":[";
        for (size_t i = 0; i < reached.size(); ++i) {
            std::snprintf(buf, sizeof buf, "%s[%d,%.6g]", i ? "," : "", reached[i].first, reached[i].second);
            j += buf;
        }
        j += "]";
    }
    j += "}";
    std::printf("%s\n", j.c_str());
    return 0;
}
