// ComposedShader programs (composed_shaders.hpp).
#include "composed_shaders.hpp"

#include "base/data_url.hpp"
#include "base/url.hpp"
#include "scene/node_access.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <functional>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

namespace gs::render::detail {

namespace {

bool uses(std::string_view source, std::string_view name) {
  for (std::size_t at = source.find(name); at != std::string_view::npos;
       at = source.find(name, at + 1)) {
    const std::size_t end = at + name.size();
    const auto word = [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    if ((at == 0 || !word(source[at - 1])) && (end >= source.size() || !word(source[end])))
      return true;
  }
  return false;
}

/// The `#version` number of `source` (0 when absent) and whether it says `es`; the
/// directive's line is blanked in `body` when it is translated.
struct VersionLine {
  int number = 0;
  bool es = false;
};

VersionLine versionOf(std::string_view source) {
  VersionLine v;
  const std::size_t at = source.find("#version");
  if (at == std::string_view::npos) return v;
  std::size_t i = at + 8;
  while (i < source.size() && (source[i] == ' ' || source[i] == '\t')) ++i;
  while (i < source.size() && source[i] >= '0' && source[i] <= '9')
    v.number = v.number * 10 + (source[i++] - '0');
  const std::size_t eol = source.find('\n', at);
  v.es = source.substr(i, eol == std::string_view::npos ? std::string_view::npos : eol - i)
             .find("es") != std::string_view::npos;
  return v;
}

// OpenGL 2 inputs and uniforms: {built-in, declaration of its stand-in}.
struct Builtin {
  std::string_view name, declaration;
};
constexpr std::array kVertexInputs = {
    Builtin{"gl_Vertex", "in vec4 gs_Vertex;\n#define gl_Vertex gs_Vertex\n"},
    Builtin{"gl_Normal", "in vec3 gs_Normal;\n#define gl_Normal gs_Normal\n"},
    Builtin{"gl_Color", "in vec4 gs_Color;\n#define gl_Color gs_Color\n"},
    Builtin{"gl_MultiTexCoord0",
            "in vec4 gs_MultiTexCoord0;\n#define gl_MultiTexCoord0 gs_MultiTexCoord0\n"},
    Builtin{"gl_MultiTexCoord1",
            "in vec4 gs_MultiTexCoord1;\n#define gl_MultiTexCoord1 gs_MultiTexCoord1\n"},
};
constexpr std::array kMatrices = {
    Builtin{"gl_ModelViewMatrix",
            "uniform mat4 gs_ModelViewMatrix;\n#define gl_ModelViewMatrix gs_ModelViewMatrix\n"},
    Builtin{"gl_ProjectionMatrix",
            "uniform mat4 gs_ProjectionMatrix;\n#define gl_ProjectionMatrix gs_ProjectionMatrix\n"},
    Builtin{"gl_ModelViewProjectionMatrix",
            "uniform mat4 gs_ModelViewProjectionMatrix;\n"
            "#define gl_ModelViewProjectionMatrix gs_ModelViewProjectionMatrix\n"},
    Builtin{"gl_NormalMatrix",
            "uniform mat3 gs_NormalMatrix;\n#define gl_NormalMatrix gs_NormalMatrix\n"},
};
constexpr std::string_view kFunctions =
    "#define texture2D texture\n#define texture3D texture\n#define textureCube texture\n"
    "#define shadow2D texture\n#define texture2DProj textureProj\n"
    "#define texture2DLod textureLod\n#define textureCubeLod textureLod\n";

constexpr std::array<std::pair<std::string_view, const char*>, 3> kX3dConstants = {
    std::pair<std::string_view, const char*>{"x3d_MaxClipPlanes", "6"},
    {"x3d_MaxLights", "8"},
    {"x3d_MaxTextures", "4"}};

// Vertex data locations of GpuMesh (mesh_gpu.cpp) and the names a shader may give them.
struct AttributeNames {
  GLuint location;
  std::array<const char*, 4> names;
};
constexpr std::array kAttributes = {
    AttributeNames{0, {"castle_Vertex", "x3d_Vertex", "gs_Vertex", nullptr}},
    AttributeNames{1, {"castle_Normal", "x3d_Normal", "gs_Normal", nullptr}},
    AttributeNames{2, {"castle_Color", "x3d_Color", "gs_Color", nullptr}},
    AttributeNames{
        3, {"castle_MultiTexCoord0", "x3d_TexCoord", "x3d_MultiTexCoord0", "gs_MultiTexCoord0"}},
    AttributeNames{4,
                   {"castle_MultiTexCoord1", "x3d_MultiTexCoord1", "gs_MultiTexCoord1", nullptr}},
};
/// Attributes of other names (the vertex attribute nodes', GpuMesh::bindAttributes) go
/// from here up, clear of GpuMesh's own.
constexpr GLuint kFirstOtherAttribute = 8;

std::string infoLog(GLuint object, bool program) {
  GLint length = 0;
  if (program)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  if (program)
    glGetProgramInfoLog(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
  else
    glGetShaderInfoLog(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log;
}

/// The shape of an attribute of GLSL type `type`: columns and rows (a vector: 1 column).
std::pair<int, int> shapeOf(GLenum type) {
  switch (type) {
    case GL_FLOAT:
      return {1, 1};
    case GL_FLOAT_VEC2:
      return {1, 2};
    case GL_FLOAT_VEC3:
      return {1, 3};
    case GL_FLOAT_MAT2:
      return {2, 2};
    case GL_FLOAT_MAT3:
      return {3, 3};
    case GL_FLOAT_MAT4:
      return {4, 4};
    default:
      return {1, 4};
  }
}

bool ourAttribute(std::string_view n) {
  return std::any_of(kAttributes.begin(), kAttributes.end(), [&](const auto& a) {
    return std::any_of(a.names.begin(), a.names.end(),
                       [&](const char* m) { return m != nullptr && n == m; });
  });
}

/// The active attributes of `program` that are not GpuMesh's (vertex attribute nodes',
/// X3D 4.0 clause 31.4), with their shapes and, when `located`, their locations.
std::vector<ProgramAttribute> otherAttributes(GLuint program, bool located) {
  std::vector<ProgramAttribute> out;
  GLint count = 0;
  glGetProgramiv(program, GL_ACTIVE_ATTRIBUTES, &count);
  for (GLint i = 0; i < count; ++i) {
    std::array<char, 256> name{};
    GLint size = 0;
    GLenum type = 0;
    glGetActiveAttrib(program, static_cast<GLuint>(i), static_cast<GLsizei>(name.size()), nullptr,
                      &size, &type, name.data());
    const std::string_view n(name.data());
    if (n.starts_with("gl_") || ourAttribute(n)) continue;
    ProgramAttribute a;
    a.name = std::string(n);
    std::tie(a.columns, a.rows) = shapeOf(type);
    if (located) {
      const GLint l = glGetAttribLocation(program, name.data());
      if (l < 0) continue;
      a.location = static_cast<GLuint>(l);
    }
    out.push_back(std::move(a));
  }
  return out;
}

/// Links `shaders` into a new program with GpuMesh's attribute locations; other active
/// attributes (the vertex attribute nodes') are given locations from kFirstOtherAttribute
/// up, a matrix as many as it has columns, and listed in `attributes`. Throws with the
/// linker's log.
GLuint linkProgram(const std::vector<GLuint>& shaders, std::vector<ProgramAttribute>& attributes) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  for (const AttributeNames& a : kAttributes)
    for (const char* name : a.names)
      if (name != nullptr) glBindAttribLocation(program, a.location, name);
  glLinkProgram(program);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) {
    const std::vector<ProgramAttribute> others = otherAttributes(program, false);
    GLuint next = kFirstOtherAttribute;
    for (const ProgramAttribute& a : others) {
      glBindAttribLocation(program, next, a.name.c_str());
      next += static_cast<GLuint>(a.columns);
    }
    if (!others.empty()) {
      glLinkProgram(program);
      glGetProgramiv(program, GL_LINK_STATUS, &ok);
    }
  }
  if (ok != GL_TRUE) {
    const std::string log = infoLog(program, true);
    glDeleteProgram(program);
    throw std::runtime_error("the shader does not link: " + log);
  }
  attributes = otherAttributes(program, true);
  return program;
}

GLuint compileStage(ShaderStage stage, const std::string& source, const std::string& url) {
  const GLuint shader =
      glCreateShader(stage == ShaderStage::vertex ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
  const std::string translated = translateGlsl(source, stage);
  const char* text = translated.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = infoLog(shader, false);
    glDeleteShader(shader);
    const std::string shown =
        base::isDataUrl(url) && url.size() > 48 ? url.substr(0, 48) + "..." : url;
    throw std::runtime_error(shown + " does not compile: " + log);
  }
  return shader;
}

// What the program is built from: the parts' revisions (not the shader's own, which every
// routed uniform value bumps); for a ProgramShader a hash of its programs' types and urls
// (their revisions count their uniform fields too), remembered in `hashes` per program
// revision so that inline sources are not hashed every frame.
std::uint64_t sourcesRevision(const vrml::Node& shader,
                              vrml::NodeMap<std::pair<std::uint64_t, std::uint64_t>>& hashes) {
  std::uint64_t r = 1;
  if (shader.typeId() == vrml::NodeTypeId::ProgramShader) {
    const std::hash<std::string_view> hash;
    for (const vrml::NodePtr& program : shader.mfnode("programs")) {
      r = r * 1000003u + (program ? program->serial() : 0u);
      if (!program) continue;
      auto [known, fresh] = hashes.try_emplace(program.get(), program->revision(), 0);
      if (fresh || known->second.first != program->revision()) {
        std::uint64_t h = hash(scene::sfString(*program, "type"));
        for (const std::string& url : scene::mfString(*program, "url")) h = h * 31u + hash(url);
        known->second = {program->revision(), h};
      }
      r = r * 31u + known->second.second;
    }
    return r;
  }
  for (const vrml::NodePtr& part : shader.mfnode("parts"))
    r = r * 1000003u + (part ? part->serial() * 31u + part->revision() : 0u);
  return r;
}

bool isGlsl(const vrml::Node& shader) {
  const std::string& language = scene::sfString(shader, "language");
  return language.empty() || language == "GLSL";
}

/// Sets uniform array `location` from the values `a` as V (float or a glm float vector,
/// tightly packed floats): as they are when they are V, else converted (doubles).
template <class V, class A, class Set>
void setFloats(const A& a, GLint location, Set set) {
  if (a.empty()) return;
  const auto n = static_cast<GLsizei>(a.size());
  if constexpr (std::is_same_v<typename A::value_type, V>) {
    set(location, n, reinterpret_cast<const float*>(a.data()));
  } else {
    const std::vector<V> f(a.begin(), a.end());
    set(location, n, reinterpret_cast<const float*>(f.data()));
  }
}

/// Sets uniform matrix array `location` from (double or float) matrices `a` as M.
// An SF/MF matrix field reaches its uniform with GLSL's column k holding the field's
// values k*N .. k*N+N-1 in file order (the file's rows: X3D 5.3.10 writes them row by
// row), as X_ITE passes them: the matrix a row-vector convention writes is then the same
// transformation in GLSL's column-vector one.
constexpr GLboolean kFileOrder = GL_TRUE;

template <class M, class A, class Set>
void setMatrices(const A& a, GLint location, Set set) {
  if (a.empty()) return;
  std::vector<M> f(a.begin(), a.end());
  set(location, static_cast<GLsizei>(f.size()), kFileOrder, glm::value_ptr(f[0]));
}

}  // namespace

std::string translateGlsl(std::string_view source, ShaderStage stage) {
  const VersionLine version = versionOf(source);
  if (version.number >= 330 && !version.es) return std::string(source);
  const bool vertex = stage == ShaderStage::vertex;
  std::string head = "#version 330 core\n";
  // #version and #extension directives come before any other token: blank them in the
  // body (keeping its line count) and put the extensions first.
  std::string body(source);
  for (std::size_t at = body.find('#'); at != std::string::npos; at = body.find('#', at + 1)) {
    std::size_t start = at;
    while (start > 0 && (body[start - 1] == ' ' || body[start - 1] == '\t')) --start;
    if (start > 0 && body[start - 1] != '\n') continue;
    std::size_t word = at + 1;
    while (word < body.size() && (body[word] == ' ' || body[word] == '\t')) ++word;
    const bool isVersion = body.compare(word, 7, "version") == 0;
    const bool isExtension = body.compare(word, 9, "extension") == 0;
    if (!isVersion && !isExtension) continue;
    const std::size_t eol = std::min(body.find('\n', at), body.size());
    if (isExtension) head += body.substr(at, eol - at) + "\n";
    body.replace(at, eol - at, std::string(eol - at, ' '));
  }
  head += vertex ? "#define attribute in\n#define varying out\n" : "#define varying in\n";
  head += kFunctions;
  // X_ITE's built-in constants (its custom shaders' x3d_Max*: X_ITE 15's defaults).
  for (const auto& [name, value] : kX3dConstants)
    if (uses(source, name)) head += "#define " + std::string(name) + " " + value + "\n";
  if (vertex)
    for (const Builtin& b : kVertexInputs)
      if (uses(source, b.name)) head += b.declaration;
  const bool ftransform = vertex && uses(source, "ftransform");
  for (const Builtin& b : kMatrices)
    if (uses(source, b.name) || (ftransform && b.name == "gl_ModelViewProjectionMatrix"))
      head += b.declaration;
  if (ftransform) {
    if (!uses(source, "gl_Vertex")) head += kVertexInputs[0].declaration;
    head += "#define ftransform() (gs_ModelViewProjectionMatrix * gs_Vertex)\n";
  }
  // Varyings OpenGL 2 built in: the front colour and the texture coordinates.
  const std::string_view io = vertex ? "out" : "in";
  if (vertex ? uses(source, "gl_FrontColor") : uses(source, "gl_Color"))
    head += std::string(io) + " vec4 gs_FrontColor;\n#define " +
            (vertex ? "gl_FrontColor" : "gl_Color") + " gs_FrontColor\n";
  if (uses(source, "gl_TexCoord"))
    head += std::string(io) + " vec4 gs_TexCoord[4];\n#define gl_TexCoord gs_TexCoord\n";
  if (!vertex && uses(source, "gl_FragColor"))
    head += "out vec4 gs_FragColor;\n#define gl_FragColor gs_FragColor\n";
  if (!vertex && uses(source, "gl_FragData"))
    head += "out vec4 gs_FragData[1];\n#define gl_FragData gs_FragData\n";
  return head + "#line 1\n" + body;
}

const UserProgram* UserPrograms::find(const vrml::Node& appearance, const std::string& baseUrl,
                                      scene::SceneTraversal& traversal, base::Fetcher* fetcher) {
  using vrml::NodeTypeId;
  for (const vrml::NodePtr& shader : appearance.mfnode("shaders")) {
    if (!shader || shader->unresolved) continue;
    const NodeTypeId type = shader->typeId();
    if (type == NodeTypeId::PackagedShader) {
      Entry& e = programs_[shader.get()];
      if (!e.failed) {
        skipPackaged(*shader, traversal);
        noteState(*shader, false, false);
      }
      e.failed = true;
      continue;
    }
    if ((type != NodeTypeId::ComposedShader && type != NodeTypeId::ProgramShader) ||
        !isGlsl(*shader))
      continue;
    Entry& e = programs_[shader.get()];
    const std::uint64_t revision = sourcesRevision(*shader, sourceHashes_);
    if (e.program.id != 0 && e.partsRevision == revision) {
      if (!e.selectedNoted) noteState(*shader, true, true);  // once, not per shape and frame
      e.selectedNoted = true;
      return &e.program;
    }
    if (e.failed && e.partsRevision == revision) continue;
    if (e.program.id != 0) glDeleteProgram(e.program.id);
    e = Entry{};
    bool pending = false;
    const UserProgram* p = build(*shader, e, baseUrl, traversal, fetcher, pending);
    if (pending) return nullptr;  // not yet: the built-in shading meanwhile
    e.partsRevision = revision;
    noteState(*shader, p != nullptr, p != nullptr);
    if (p != nullptr) return p;
  }
  return nullptr;
}

void UserPrograms::noteState(const vrml::Node& shader, bool valid, bool selected) {
  SentState& sent = sent_[&shader];
  if (sent.valid != valid) {
    sent.valid = valid;
    outputs_.push_back(
        {&shader, "isValid", vrml::FieldValue::make<vrml::FieldType::SFBool>(valid)});
  }
  // isSelected FALSE only for a shader that said TRUE.
  if (sent.selected.value_or(false) != selected) {
    sent.selected = selected;
    outputs_.push_back(
        {&shader, "isSelected", vrml::FieldValue::make<vrml::FieldType::SFBool>(selected)});
  }
}

void UserPrograms::skipPackaged(const vrml::Node& shader, scene::SceneTraversal& traversal) {
  const std::string& language = scene::sfString(shader, "language");
  const std::vector<std::string>& urls = scene::mfString(shader, "url");
  std::string url = urls.empty() ? std::string() : urls.front();
  if (base::isDataUrl(url) && url.size() > 48) url = url.substr(0, 48) + "...";
  traversal.report(vrml::Severity::warning, shader.location,
                   "PackagedShader not used: " +
                       (language.empty() ? std::string("it names no language")
                                         : "its language \"" + language + "\" is not one") +
                       " this browser runs (GLSL, in ComposedShader and ProgramShader, is)" +
                       (url.empty() ? "" : "; url \"" + url + "\"") +
                       "; the next shader of the list is tried");
}

const UserProgram* UserPrograms::build(const vrml::Node& shader, Entry& entry,
                                       const std::string& baseUrl, scene::SceneTraversal& traversal,
                                       base::Fetcher* fetcher, bool& pending) {
  // A ComposedShader's ShaderParts, or a ProgramShader's ShaderPrograms: each a stage's
  // source (clauses 31.4.2, 31.4.6).
  const bool composed = shader.typeId() == vrml::NodeTypeId::ComposedShader;
  const std::string kind = composed ? "ComposedShader" : "ProgramShader";
  const vrml::NodeTypeId sourceType =
      composed ? vrml::NodeTypeId::ShaderPart : vrml::NodeTypeId::ShaderProgram;
  const char* sourceWord = composed ? " part " : " program ";
  std::vector<GLuint> compiled;
  const auto fail = [&](const std::string& why) {
    for (GLuint s : compiled) glDeleteShader(s);
    entry.failed = true;
    traversal.report(vrml::Severity::warning, shader.location,
                     kind + " not used: " + why + "; the shape is drawn without it");
    return nullptr;
  };
  std::vector<const vrml::Node*> sources;
  bool vertex = false, fragment = false;
  for (const vrml::NodePtr& part :
       (composed ? shader.mfnode("parts") : shader.mfnode("programs"))) {
    if (!part || part->unresolved || part->typeId() != sourceType) continue;
    sources.push_back(part.get());
    const std::string& type = scene::sfString(*part, "type");
    vertex = vertex || type == "VERTEX";
    fragment = fragment || type == "FRAGMENT";
  }
  // A ProgramShader is one vertex and one fragment program linked together; without
  // either there is no built-in stage to stand in (31.4.6).
  if (!composed && (!vertex || !fragment))
    return fail(std::string("it has no ") + (vertex ? "FRAGMENT" : "VERTEX") +
                " ShaderProgram (both are needed)");
  for (const vrml::Node* part : sources) {
    const std::string& type = scene::sfString(*part, "type");
    if (type != "VERTEX" && type != "FRAGMENT")
      return fail(std::string(composed ? "ShaderPart" : "ShaderProgram") + " type \"" + type +
                  "\" is not supported (VERTEX and FRAGMENT are)");
    const ShaderStage stage = type == "VERTEX" ? ShaderStage::vertex : ShaderStage::fragment;
    std::string failures;
    bool done = false;
    const std::string& partBase = part->urlBaseOr(baseUrl);  // its file's (Node::urlBase)
    for (const std::string& reference : scene::mfString(*part, "url")) {
      if (reference.empty()) continue;
      const std::string url = base::resolveUrl(partBase, reference);
      const base::Fetched got =
          base::fetcherOr(fetcher).fetch(url, partBase, base::FetchMode::background);
      if (got.pending()) {
        pending = true;
        for (GLuint s : compiled) glDeleteShader(s);
        return nullptr;
      }
      if (!got.ready()) {
        failures += (failures.empty() ? "" : "; ") + got.error;
        continue;
      }
      try {
        compiled.push_back(compileStage(stage, got.bytes, url));
        done = true;
        break;
      } catch (const std::exception& e) {
        failures += (failures.empty() ? "" : "; ") + std::string(e.what());
      }
    }
    if (!done)
      return fail("its " + type + sourceWord + (failures.empty() ? "has no url" : failures));
  }
  if (compiled.empty()) return fail("it has no VERTEX or FRAGMENT part");
  GLuint id = 0;
  std::vector<ProgramAttribute> attributes;
  try {
    id = linkProgram(compiled, attributes);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  for (GLuint s : compiled) glDeleteShader(s);
  UserProgram& p = entry.program;
  p.id = id;
  p.shader = &shader;
  p.attributes = std::move(attributes);
  const auto locations = [&](std::string_view suffix) {
    std::vector<GLint> out;
    for (std::string_view prefix : {"castle_", "x3d_", "gs_"}) {
      const GLint l = glGetUniformLocation(id, (std::string(prefix) + std::string(suffix)).c_str());
      if (l >= 0) out.push_back(l);
    }
    return out;
  };
  p.modelView = locations("ModelViewMatrix");
  p.projection = locations("ProjectionMatrix");
  p.normalMatrix = locations("NormalMatrix");
  p.modelViewProjection = locations("ModelViewProjectionMatrix");
  // X_ITE's texture uniforms (its custom shaders): the Appearance's texture, its count and
  // its texture matrix, each as element 0 of X_ITE's arrays.
  const auto located = [&](const char* name) { return glGetUniformLocation(id, name); };
  p.numTextures = located("x3d_NumTextures");
  p.textureMatrix = located("x3d_TextureMatrix[0]");
  p.texture2D = located("x3d_Texture2D[0]");
  p.texture3D = located("x3d_Texture3D[0]");
  p.textureCube = located("x3d_TextureCube[0]");
  // The fields as uniforms (31.2.3): the ComposedShader's, or each ShaderProgram's own.
  GLint unit = 1;  // Appearance.texture is on 0
  const auto addFields = [&](const vrml::Node& node) {
    const std::vector<vrml::FieldSpec>& specs = node.type().fields;
    for (std::size_t i = 0; i < specs.size() && i < node.fieldCount(); ++i) {
      if (specs[i].access == vrml::AccessType::eventOut ||
          specs[i].access == vrml::AccessType::eventIn)
        continue;
      const GLint location = glGetUniformLocation(id, specs[i].name.c_str());
      if (location < 0) continue;
      const bool texture = specs[i].type == vrml::FieldType::SFNode;
      if (texture && unit >= kUserTexture3DUnit) continue;
      p.fields.push_back({&node, i, location, texture ? unit++ : -1});
    }
  };
  if (composed)
    addFields(shader);
  else
    for (const vrml::Node* program : sources) addFields(*program);
  return &p;
}

void UserPrograms::use(const UserProgram& p, const glm::mat4& modelView,
                       const glm::mat4& projection, const GpuTexture* texture,
                       const glm::mat4& textureMatrix, TextureCache& textures,
                       const std::string& baseUrl, scene::SceneTraversal& traversal,
                       base::Fetcher* fetcher) {
  glUseProgram(p.id);
  const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(modelView));
  const glm::mat4 modelViewProjection = projection * modelView;
  for (GLint l : p.modelView) glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(modelView));
  for (GLint l : p.projection) glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(projection));
  for (GLint l : p.normalMatrix) glUniformMatrix3fv(l, 1, GL_FALSE, glm::value_ptr(normalMatrix));
  for (GLint l : p.modelViewProjection)
    glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(modelViewProjection));
  for (const UserProgram::FieldUniform& f : p.fields) {
    const vrml::FieldValue& v = f.node->fieldAt(f.field);
    using T = vrml::FieldType;
    const GLint l = f.location;
    switch (v.type()) {
      case T::SFBool:
        glUniform1i(l, v.get<T::SFBool>() ? 1 : 0);
        break;
      case T::SFInt32:
        glUniform1i(l, v.get<T::SFInt32>());
        break;
      case T::SFFloat:
        glUniform1f(l, v.get<T::SFFloat>());
        break;
      case T::SFDouble:
        glUniform1f(l, static_cast<float>(v.get<T::SFDouble>()));
        break;
      case T::SFTime:
        glUniform1f(l, static_cast<float>(v.get<T::SFTime>()));
        break;
      case T::SFVec2f:
        glUniform2fv(l, 1, glm::value_ptr(v.get<T::SFVec2f>()));
        break;
      case T::SFVec3f:
        glUniform3fv(l, 1, glm::value_ptr(v.get<T::SFVec3f>()));
        break;
      case T::SFColor:
        glUniform3fv(l, 1, glm::value_ptr(v.get<T::SFColor>()));
        break;
      case T::SFVec2d:
        glUniform2fv(l, 1, glm::value_ptr(glm::vec2(v.get<T::SFVec2d>())));
        break;
      case T::SFVec3d:
        glUniform3fv(l, 1, glm::value_ptr(glm::vec3(v.get<T::SFVec3d>())));
        break;
      case T::SFVec4f:
        glUniform4fv(l, 1, glm::value_ptr(v.get<T::SFVec4f>()));
        break;
      case T::SFVec4d:
        glUniform4fv(l, 1, glm::value_ptr(glm::vec4(v.get<T::SFVec4d>())));
        break;
      case T::SFColorRGBA:
        glUniform4fv(l, 1, glm::value_ptr(v.get<T::SFColorRGBA>()));
        break;
      case T::SFRotation:
        glUniform4fv(l, 1, glm::value_ptr(v.get<T::SFRotation>()));
        break;
      case T::SFMatrix3f:
        glUniformMatrix3fv(l, 1, kFileOrder, glm::value_ptr(v.get<T::SFMatrix3f>()));
        break;
      case T::SFMatrix3d:
        glUniformMatrix3fv(l, 1, kFileOrder, glm::value_ptr(glm::mat3(v.get<T::SFMatrix3d>())));
        break;
      case T::SFMatrix4f:
        glUniformMatrix4fv(l, 1, kFileOrder, glm::value_ptr(v.get<T::SFMatrix4f>()));
        break;
      case T::SFMatrix4d:
        glUniformMatrix4fv(l, 1, kFileOrder, glm::value_ptr(glm::mat4(v.get<T::SFMatrix4d>())));
        break;
      case T::MFFloat:
        setFloats<float>(v.get<T::MFFloat>(), l, glUniform1fv);
        break;
      case T::MFInt32: {
        const auto& a = v.get<T::MFInt32>();
        if (!a.empty()) glUniform1iv(l, static_cast<GLsizei>(a.size()), a.data());
        break;
      }
      case T::MFVec2f:
        setFloats<glm::vec2>(v.get<T::MFVec2f>(), l, glUniform2fv);
        break;
      case T::MFVec3f:
        setFloats<glm::vec3>(v.get<T::MFVec3f>(), l, glUniform3fv);
        break;
      case T::MFColor:
        setFloats<glm::vec3>(v.get<T::MFColor>(), l, glUniform3fv);
        break;
      case T::MFVec4f:
        setFloats<glm::vec4>(v.get<T::MFVec4f>(), l, glUniform4fv);
        break;
      case T::MFColorRGBA:
        setFloats<glm::vec4>(v.get<T::MFColorRGBA>(), l, glUniform4fv);
        break;
      case T::MFRotation:
        setFloats<glm::vec4>(v.get<T::MFRotation>(), l, glUniform4fv);
        break;
      case T::MFBool: {
        const std::vector<bool>& a = v.get<T::MFBool>();
        const std::vector<GLint> ints(a.begin(), a.end());
        if (!ints.empty()) glUniform1iv(l, static_cast<GLsizei>(ints.size()), ints.data());
        break;
      }
      case T::MFDouble:
        setFloats<float>(v.get<T::MFDouble>(), l, glUniform1fv);
        break;
      case T::MFTime:
        setFloats<float>(v.get<T::MFTime>(), l, glUniform1fv);
        break;
      case T::MFVec2d:
        setFloats<glm::vec2>(v.get<T::MFVec2d>(), l, glUniform2fv);
        break;
      case T::MFVec3d:
        setFloats<glm::vec3>(v.get<T::MFVec3d>(), l, glUniform3fv);
        break;
      case T::MFVec4d:
        setFloats<glm::vec4>(v.get<T::MFVec4d>(), l, glUniform4fv);
        break;
      case T::MFMatrix3f:
        setMatrices<glm::mat3>(v.get<T::MFMatrix3f>(), l, glUniformMatrix3fv);
        break;
      case T::MFMatrix4f:
        setMatrices<glm::mat4>(v.get<T::MFMatrix4f>(), l, glUniformMatrix4fv);
        break;
      case T::MFMatrix3d:
        setMatrices<glm::mat3>(v.get<T::MFMatrix3d>(), l, glUniformMatrix3fv);
        break;
      case T::MFMatrix4d:
        setMatrices<glm::mat4>(v.get<T::MFMatrix4d>(), l, glUniformMatrix4fv);
        break;
      case T::SFNode: {
        const vrml::NodePtr& n = v.get<T::SFNode>();
        if (!n || n->unresolved || f.unit < 0 || !n->is(vrml::AbstractType::X3DTextureNode)) break;
        const GpuTexture& t = textures.get(*n, baseUrl, traversal, fetcher);
        if (t.components == 0) break;
        glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(f.unit));
        glBindTexture(t.volume ? GL_TEXTURE_3D
                      : t.cube ? GL_TEXTURE_CUBE_MAP
                               : GL_TEXTURE_2D,
                      t.id);
        glUniform1i(l, f.unit);
        break;
      }
      default:
        break;
    }
  }
  glActiveTexture(GL_TEXTURE0);
  if (texture != nullptr && !texture->volume && !texture->cube)
    glBindTexture(GL_TEXTURE_2D, texture->id);
  // X_ITE's names for the Appearance's texture (units as the built-in programs use them).
  const bool textured = texture != nullptr && texture->components > 0;
  if (p.numTextures >= 0) glUniform1i(p.numTextures, textured ? 1 : 0);
  if (p.textureMatrix >= 0)
    glUniformMatrix4fv(p.textureMatrix, 1, GL_FALSE, glm::value_ptr(textureMatrix));
  if (p.texture2D >= 0) glUniform1i(p.texture2D, 0);
  if (textured && texture->volume && p.texture3D >= 0) {
    glActiveTexture(GL_TEXTURE0 + kUserTexture3DUnit);
    glBindTexture(GL_TEXTURE_3D, texture->id);
    glUniform1i(p.texture3D, kUserTexture3DUnit);
  }
  if (textured && texture->cube && p.textureCube >= 0) {
    glActiveTexture(GL_TEXTURE0 + kUserTextureCubeUnit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture->id);
    glUniform1i(p.textureCube, kUserTextureCubeUnit);
  }
  glActiveTexture(GL_TEXTURE0);
}

void UserPrograms::release() {
  for (auto& [key, e] : programs_)
    if (e.program.id != 0) glDeleteProgram(e.program.id);
  programs_.clear();
  sourceHashes_.clear();
}

}  // namespace gs::render::detail
