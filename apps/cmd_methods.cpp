// tetrender methods [NAME]: the scene file's rendering methods and the keys each takes (the
// tables of pipeline/methods/; docs/scene-file.md shows the same text).
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <pipeline/methods/method.h>

#include <cstdio>
#include <memory>
#include <string>

namespace tr::apps {

std::function<int()> add_methods_command(CLI::App& app) {
    auto name = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand(
        "methods", "The scene file's rendering methods and the keys each takes (markdown)");
    cmd->add_option("name", *name, "Only this method (default: every one)");
    return [name] {
        if (name->empty()) {
            std::fputs(methods_markdown().c_str(), stdout);
            return kExitOk;
        }
        const RenderMethod* method = find_method(*name);
        if (!method) {
            std::string names;
            for (const std::string& n : method_names()) names += (names.empty() ? "" : ", ") + n;
            std::fprintf(stderr, "tetrender methods: no method '%s' (methods: %s)\n", name->c_str(),
                         names.c_str());
            return kExitUsage;
        }
        std::fputs(method_keys_markdown(method->name(), method->keys()).c_str(), stdout);
        return kExitOk;
    };
}

}  // namespace tr::apps
