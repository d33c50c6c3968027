// Writes a big synthetic triangle mesh as binary little-endian PLY for the out-of-core mesh
// figures (tests/bench/ooc_mesh.sh, docs/out-of-core.md "Meshes"): a bumpy torus,
// R = 1, r = 0.35, radius modulated by 0.04 sin(7u) cos(5v) plus a fine ripple, cut into
// an N x M grid of quads, two triangles each; with --colors, a vertex colour from the
// position (hundreds of thousands of distinct triangle colours: the out-of-core encode
// counts them in half of --memory, 40 bytes each).
// --soup writes every triangle with three vertices of its own (no sharing: 3 vertices per
// triangle, the worst case for the vertex copy), else the grid's shared vertices. Prints
// the counts, the file size and the write rate.
//
//   make_mesh_soup --triangles 20000000 [--soup] [--colors] OUT.ply
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Vertex {
  float x, y, z;
  std::uint8_t r, g, b;
};

Vertex at(std::uint64_t i, std::uint64_t j, std::uint64_t n, std::uint64_t m) {
  const double u = 2.0 * M_PI * static_cast<double>(i % n) / static_cast<double>(n);
  const double v = 2.0 * M_PI * static_cast<double>(j % m) / static_cast<double>(m);
  const double r =
      0.35 + 0.04 * std::sin(7 * u) * std::cos(5 * v) + 0.004 * std::sin(97 * u + 61 * v);
  const double x = (1.0 + r * std::cos(v)) * std::cos(u), y = (1.0 + r * std::cos(v)) * std::sin(u),
               z = r * std::sin(v);
  const auto c = [](double t) { return static_cast<std::uint8_t>(std::lround(127.5 + 127.5 * t)); };
  return {static_cast<float>(x),
          static_cast<float>(y),
          static_cast<float>(z),
          c(x / 1.4),
          c(y / 1.4),
          c(z / 0.4)};
}

class Out {
 public:
  Out(std::FILE* f, bool colors) : f_(f), colors_(colors) { buf_.reserve(1 << 20); }
  ~Out() { flush(); }
  template <typename T>
  void put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    buf_.insert(buf_.end(), p, p + sizeof v);
    if (buf_.size() >= (1 << 20)) flush();
  }
  void vertex(const Vertex& v) {
    put(v.x), put(v.y), put(v.z);
    if (colors_) put(v.r), put(v.g), put(v.b);
  }
  void flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) {
      std::perror("write");
      std::exit(1);
    }
    buf_.clear();
  }

 private:
  std::FILE* f_;
  bool colors_;
  std::vector<char> buf_;
};

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t triangles = 1000000;
  bool soup = false, colors = false;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--triangles") && i + 1 < argc)
      triangles = std::strtoull(argv[++i], nullptr, 10);
    else if (!std::strcmp(argv[i], "--soup"))
      soup = true;
    else if (!std::strcmp(argv[i], "--colors"))
      colors = true;
    else
      path = argv[i];
  }
  if (path.empty() || triangles < 2) {
    std::fprintf(stderr, "usage: make_mesh_soup --triangles N [--soup] [--colors] OUT.ply\n");
    return 2;
  }
  // n x m quads with n = 3 m (the torus's long way round), 2 n m >= triangles.
  std::uint64_t m = static_cast<std::uint64_t>(std::ceil(std::sqrt(triangles / 6.0)));
  std::uint64_t n = (triangles / 2 + m - 1) / m;
  const std::uint64_t tris = 2 * n * m;
  const std::uint64_t vertices = soup ? 3 * tris : n * m;
  const auto t0 = std::chrono::steady_clock::now();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    std::perror(path.c_str());
    return 1;
  }
  std::fprintf(f,
               "ply\nformat binary_little_endian 1.0\ncomment make_mesh_soup: bumpy torus\n"
               "element vertex %llu\nproperty float x\nproperty float y\nproperty float z\n%s"
               "element face %llu\nproperty list uchar int vertex_indices\nend_header\n",
               static_cast<unsigned long long>(vertices),
               colors ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "",
               static_cast<unsigned long long>(tris));
  {
    Out out(f, colors);
    if (soup) {
      for (std::uint64_t i = 0; i < n; ++i)
        for (std::uint64_t j = 0; j < m; ++j) {
          const Vertex a = at(i, j, n, m), b = at(i + 1, j, n, m), c = at(i + 1, j + 1, n, m),
                       d = at(i, j + 1, n, m);
          out.vertex(a), out.vertex(b), out.vertex(c);
          out.vertex(a), out.vertex(c), out.vertex(d);
        }
      for (std::uint64_t t = 0; t < tris; ++t) {
        out.put(std::uint8_t{3});
        for (std::uint64_t k = 0; k < 3; ++k) out.put(static_cast<std::int32_t>(3 * t + k));
      }
    } else {
      for (std::uint64_t i = 0; i < n; ++i)
        for (std::uint64_t j = 0; j < m; ++j) out.vertex(at(i, j, n, m));
      const auto id = [&](std::uint64_t i, std::uint64_t j) {
        return static_cast<std::int32_t>((i % n) * m + (j % m));
      };
      for (std::uint64_t i = 0; i < n; ++i)
        for (std::uint64_t j = 0; j < m; ++j) {
          out.put(std::uint8_t{3}), out.put(id(i, j)), out.put(id(i + 1, j)),
              out.put(id(i + 1, j + 1));
          out.put(std::uint8_t{3}), out.put(id(i, j)), out.put(id(i + 1, j + 1)),
              out.put(id(i, j + 1));
        }
    }
  }
  const long bytes = std::ftell(f);
  std::fclose(f);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: %llu triangles, %llu vertices (%s), %.1f MiB, written in %.1f s\n", path.c_str(),
              static_cast<unsigned long long>(tris), static_cast<unsigned long long>(vertices),
              soup ? "soup" : "shared", bytes / 1048576.0, s);
  return 0;
}
