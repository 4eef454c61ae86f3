// Shader compile and link (link_program, also the kiosk overlay's) and the
// renderer's program table.
#include "kiosk/render/programs.h"

#include <algorithm>
#include <cstdio>
#include <string_view>
#include <utility>

#include "kiosk/render/program_binary.h"
#include "kiosk/render/renderer.h"

namespace body::render {
namespace {

// A shader's or program's info log on one line; the object is deleted.
std::string take_info_log(GLuint id, bool program) {
    char log[2048] = {};
    if (program) {
        glGetProgramInfoLog(id, sizeof(log), nullptr, log);
        glDeleteProgram(id);
    } else {
        glGetShaderInfoLog(id, sizeof(log), nullptr, log);
        glDeleteShader(id);
    }
    std::string one_line(log);
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    return one_line;
}

Result<GLuint> compile(GLenum type, const char* src, const std::string& label) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) return runtime_error("shader " + label + ": compile failed: " + take_info_log(s, false));
    return s;
}

// `defines` ("#define X 1\n" lines) go after each source's #version line;
// defines that begin with a #version line replace the source's.
std::string with_defines(const char* source, const char* defines) {
    std::string text(source);
    if (!defines || !*defines) return text;
    const size_t eol = text.find('\n');
    if (std::string_view(defines).starts_with("#version") && text.starts_with("#version"))
        return eol == std::string::npos ? defines : text.replace(0, eol + 1, defines);
    return eol == std::string::npos ? text + "\n" + defines : text.insert(eol + 1, defines);
}

Result<Program> link(const std::string& vert, const std::string& frag, const char* defines) {
    const char* vs_source = shader_source(vert);
    const char* fs_source = shader_source(frag);
    if (!vs_source || !fs_source)
        return runtime_error("shader " + (vs_source ? frag : vert) + ": not embedded in this build");
    const std::string vs_text = with_defines(vs_source, defines), fs_text = with_defines(fs_source, defines);
    const char* vs = vs_text.c_str();
    const char* fs = fs_text.c_str();
    const std::pair<unsigned, const char*> attributes[] = {{kPosition, "a_position"},
                                                           {kNormal, "a_normal"},
                                                           {kMorph, "a_morph"},
                                                           {kWireVertex, "a_vertex"},
                                                           {kNormalCode, "a_normal_code"}};
    auto id = link_program(vs, fs, vert + "+" + frag, attributes);
    if (!id) return id.error();
    Program p;
    p.id = id.value();
    return p;
}

}  // namespace

GLint Program::loc(const char* name) {
    auto it = locations.find(std::string_view(name));
    if (it != locations.end()) return it->second;
    GLint l = glGetUniformLocation(id, name);
    locations.emplace(name, l);
    return l;
}

Result<unsigned> link_program(const char* vertex_source, const char* fragment_source, const std::string& name,
                              std::span<const std::pair<unsigned, const char*>> attributes) {
    // The binary's key: everything the link depends on besides the driver (which checks its own).
    std::string key;
    if (!program_binary_dir().empty()) {
        key = std::string(vertex_source) + '\0' + fragment_source + '\0';
        for (const auto& [location, attribute] : attributes) key += std::to_string(location) + attribute + '\0';
        if (const GLuint id = load_program_binary(key)) return id;
    }
    auto vs = compile(GL_VERTEX_SHADER, vertex_source, name + " (vertex)");
    if (!vs) return vs.error();
    auto fs = compile(GL_FRAGMENT_SHADER, fragment_source, name + " (fragment)");
    if (!fs) {
        glDeleteShader(vs.value());
        return fs.error();
    }
    const GLuint id = glCreateProgram();
    glAttachShader(id, vs.value());
    glAttachShader(id, fs.value());
    for (const auto& [location, attribute] : attributes) glBindAttribLocation(id, location, attribute);
    if (!key.empty()) glProgramParameteri(id, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glLinkProgram(id);
    glDeleteShader(vs.value());
    glDeleteShader(fs.value());
    GLint ok = 0;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) return runtime_error("program " + name + ": link failed: " + take_info_log(id, true));
    if (!key.empty()) save_program_binary(key, id);
    return id;
}

Program deferred_program(std::string vert, std::string frag, std::string defines) {
    Program p;
    p.vert = std::move(vert);
    p.frag = std::move(frag);
    p.defines = std::move(defines);
    return p;
}

bool link_on_first_use(Program& p) {
    if (p.id) return true;
    if (p.link_failed || p.vert.empty()) return false;
    auto linked = link(p.vert, p.frag, p.defines.c_str());
    if (!linked) {
        p.link_failed = true;
        std::fprintf(stderr, "bodyview: %s\n", linked.error().message.c_str());
        return false;
    }
    p.id = linked.value().id;
    return true;
}

void defer_programs(Programs& programs, const char* defines) {
    delete_programs(programs);
    const std::string d = defines ? defines : "";
    programs.baseline = deferred_program("mesh.vert", "baseline.frag", d);
    programs.smooth = deferred_program("mesh.vert", "smooth.frag", d);
    programs.hatching = deferred_program("mesh.vert", "hatching.frag", d);
    programs.xray = deferred_program("mesh.vert", "xray.frag", d);
    programs.lines = deferred_program("lines.vert", "lines.frag", d);
    programs.wireframe = deferred_program("wireframe.vert", "wireframe.frag", d);
    programs.wireframe_buffer =
        deferred_program("wireframe.vert", "wireframe.frag", "#version 320 es\n" + d + "#define BODY_WIRE_BUFFER 1\n");
}

Status link_programs(Programs& programs, const char* defines) {
    defer_programs(programs, defines);
    for (Program* p : {&programs.baseline, &programs.smooth, &programs.hatching, &programs.xray, &programs.lines,
                       &programs.wireframe}) {
        auto linked = link(p->vert, p->frag, p->defines.c_str());
        if (!linked) {
            delete_programs(programs);
            return linked.error();
        }
        p->id = linked.value().id;
    }
    return ok_status();
}

Result<Program> link_shader_pair(const std::string& vert, const std::string& frag, const char* defines) {
    return link(vert, frag, defines);
}

void delete_programs(Programs& programs) {
    for (Program* p : {&programs.baseline, &programs.smooth, &programs.hatching, &programs.xray, &programs.lines,
                       &programs.wireframe, &programs.wireframe_buffer}) {
        if (p->id) glDeleteProgram(p->id);
        *p = Program{};
    }
}

}  // namespace body::render
