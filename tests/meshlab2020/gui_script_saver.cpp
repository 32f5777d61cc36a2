// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Writes a filter script the way MeshLab 2020.09's GUI does: the plugin is loaded by
// QPluginLoader like PluginManager does, the parameter list comes from the plugin's
// initParameterSet (what the filter dialog shows), edited values are set on it as the dialog
// does, the pair (action text, parameters) goes into a FilterScript (the document's filter
// history) and FilterScript::save writes the file (Filters > Show current filter script > Save).
//
//   gui_script_saver PLUGIN.so OUT.mlx "FILTER MENU TEXT" [name=value ...]
#include <common/filterscript.h>
#include <common/interfaces.h>
#include <common/meshmodel.h>

#include <QApplication>
#include <QPluginLoader>

#include <cstdio>

int main(int argc, char** argv)
{
    QApplication app(argc, argv);   // QActions need it; run with QT_QPA_PLATFORM=offscreen
    if (argc < 4) {
        std::fprintf(stderr, "usage: gui_script_saver PLUGIN.so OUT.mlx FILTER [name=value ...]\n");
        return 2;
    }
    QPluginLoader loader(QString::fromLocal8Bit(argv[1]));
    QObject* instance = loader.instance();
    if (instance == nullptr) {
        std::fprintf(stderr, "cannot load %s: %s\n", argv[1], qUtf8Printable(loader.errorString()));
        return 1;
    }
    auto* filter = qobject_cast<MeshFilterInterface*>(instance);
    if (filter == nullptr) {
        std::fprintf(stderr, "%s is not a MeshFilterInterface plugin\n", argv[1]);
        return 1;
    }
    QAction* action = nullptr;
    for (QAction* a : filter->actions())
        if (a->text() == QString::fromUtf8(argv[3])) action = a;
    if (action == nullptr) {
        std::fprintf(stderr, "no filter named '%s'\n", argv[3]);
        return 1;
    }

    MeshDocument md;
    md.addNewMesh("", "mesh");      // the GUI always has a current mesh when a filter runs
    RichParameterList par;
    filter->initParameterSet(action, md, par);

    for (int i = 4; i < argc; ++i) {
        const QString kv = QString::fromUtf8(argv[i]);
        const int eq = kv.indexOf('=');
        const QString name = kv.left(eq), value = kv.mid(eq + 1);
        if (eq < 0 || !par.hasParameter(name)) {
            std::fprintf(stderr, "unknown parameter '%s'\n", argv[i]);
            return 2;
        }
        const Value& old = par.getParameterByName(name).value();
        if (old.isEnum()) par.setValue(name, EnumValue(value.toInt()));
        else if (old.isBool()) par.setValue(name, BoolValue(value == "true"));
        else if (old.isInt()) par.setValue(name, IntValue(value.toInt()));
        else if (old.isFloat()) par.setValue(name, FloatValue(value.toFloat()));
        else {
            std::fprintf(stderr, "parameter '%s' has an unexpected type\n", argv[i]);
            return 2;
        }
    }

    FilterScript history;
    FilterNameParameterValuesPair entry;
    entry.first = action->text();
    entry.second = par;
    history.append(entry);
    if (!history.save(QString::fromLocal8Bit(argv[2]))) return 1;
    std::printf("saved %s (%u parameters)\n", argv[2], par.size());
    return 0;
}
