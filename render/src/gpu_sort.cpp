// The GPU radix sort of the GL splat path's depth order (see gpu_sort.hpp).
#include "gpu_sort.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include "gl_program.hpp"

namespace gs::render::detail {

namespace {

constexpr GLuint kGroup = 256;              // threads per workgroup, and digits per pass
constexpr GLuint kItems = 16;               // elements per thread in a block
constexpr GLuint kBlock = kGroup * kItems;  // elements per block
constexpr GLuint kMaxGroupsX = 65535;       // the least GL_MAX_COMPUTE_WORK_GROUP_COUNT
constexpr GLuint kMaxSplats = 0xffffffffu;  // indices are uint32

// What every program starts with: the version, the workgroup (kGroup threads), the block
// (kItems elements a thread, kBlock in all) and the workgroup's index over a 2D grid.
std::string commonSource() {
  return "#version 430 core\n#define GROUP " + std::to_string(kGroup) + "u\n#define ITEMS " +
         std::to_string(kItems) + "u\n#define BLOCK " + std::to_string(kBlock) +
         "u\nlayout(local_size_x = GROUP) in;\n"
         "uint groupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }\n";
}

// Keys: eye z made an order-preserving unsigned integer (DepthSorter's depthKey), values
// the splats' indices, both written in reverse (splat k at count - 1 - k): the stable sort
// then puts splats of equal depth in descending index order, so that the order is the exact
// reverse of DepthSorter::sortFrontToBack's, which the geometry path draws reversed and the
// cpu path composites front to back. Splats of equal depth (a voxel grid seen along an
// axis) are then blended in the same sequence on every path.
const char* const kKeysShader = R"glsl(
uniform samplerBuffer u_splats;
uniform vec4 u_row;  // row 2 of the model-view matrix: eye z = dot(u_row, (p, 1))
uniform uint u_count;
uniform bool u_subset;  // sort the splats subset[0 .. count) instead of 0 .. count
layout(std430, binding = 0) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = 1) writeonly buffer Values { uint values[]; };
layout(std430, binding = 5) readonly buffer Subset { uint subset[]; };
void main() {
  uint k = groupIndex() * GROUP + gl_LocalInvocationID.x;
  if (k >= u_count) return;
  uint i = u_subset ? subset[k] : k;
  vec3 p = texelFetch(u_splats, int(3u * i)).xyz;
  float z = (u_row.x * p.x + u_row.y * p.y) + (u_row.z * p.z + u_row.w) + 0.0;
  uint bits = floatBitsToUint(z);
  uint key = (bits & 0x80000000u) != 0u ? ~bits : (bits | 0x80000000u);
  uint at = u_count - 1u - k;
  keys[at] = isnan(z) ? 0u : key;
  values[at] = i;
}
)glsl";

// Per block, how many of its keys have each digit; stored digit-major (digit * blocks +
// block), so that one exclusive scan of the whole array gives every (digit, block) its
// first place in the output.
const char* const kHistogramShader = R"glsl(
uniform uint u_count;
uniform uint u_shift;
uniform uint u_blocks;
layout(std430, binding = 0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = 2) writeonly buffer Counts { uint counts[]; };
shared uint hist[GROUP];
void main() {
  uint t = gl_LocalInvocationID.x;
  uint block = groupIndex();
  hist[t] = 0u;
  barrier();
  uint begin = block * BLOCK;
  for (uint k = 0u; k < ITEMS; ++k) {
    uint i = begin + k * GROUP + t;
    if (i < u_count) atomicAdd(hist[(keys[i] >> u_shift) & (GROUP - 1u)], 1u);
  }
  barrier();
  if (block < u_blocks) counts[t * u_blocks + block] = hist[t];
}
)glsl";

// The exclusive prefix sum of the counts, in place, by one workgroup: each thread sums a
// contiguous run, the runs' sums are scanned, then each run is written.
const char* const kScanShader = R"glsl(
uniform uint u_length;
layout(std430, binding = 2) buffer Counts { uint counts[]; };
shared uint sums[GROUP];
void main() {
  uint t = gl_LocalInvocationID.x;
  uint per = (u_length + GROUP - 1u) / GROUP;
  uint begin = min(t * per, u_length);
  uint end = min(begin + per, u_length);
  uint sum = 0u;
  for (uint i = begin; i < end; ++i) sum += counts[i];
  sums[t] = sum;
  barrier();
  if (t == 0u) {
    uint run = 0u;
    for (uint k = 0u; k < GROUP; ++k) {
      uint s = sums[k];
      sums[k] = run;
      run += s;
    }
  }
  barrier();
  uint run = sums[t];
  for (uint i = begin; i < end; ++i) {
    uint c = counts[i];
    counts[i] = run;
    run += c;
  }
}
)glsl";

// The stable scatter: each block walks its elements 256 at a time, in order; an element's
// place is its digit's running offset plus the number of earlier elements of the same
// 256 with the same digit: each element sets its bit in its digit's 256-bit mask (8
// words), and its rank is the population count of the mask's bits below its own.
const char* const kScatterShader = R"glsl(
uniform uint u_count;
uniform uint u_shift;
uniform uint u_blocks;
layout(std430, binding = 0) readonly buffer KeysIn { uint keysIn[]; };
layout(std430, binding = 1) readonly buffer ValuesIn { uint valuesIn[]; };
layout(std430, binding = 2) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 3) writeonly buffer KeysOut { uint keysOut[]; };
layout(std430, binding = 4) writeonly buffer ValuesOut { uint valuesOut[]; };
shared uint offsets[GROUP];
shared uint added[GROUP];
shared uint masks[GROUP * (GROUP / 32u)];  // digit d's bits: masks[d * 8 .. d * 8 + 7]
void main() {
  uint t = gl_LocalInvocationID.x;
  uint block = groupIndex();
  if (block >= u_blocks) return;  // uniform per workgroup
  offsets[t] = counts[t * u_blocks + block];
  added[t] = 0u;
  for (uint w = 0u; w < GROUP / 32u; ++w) masks[t * (GROUP / 32u) + w] = 0u;
  uint word = t / 32u, bit = 1u << (t % 32u);
  barrier();
  uint begin = block * BLOCK;
  for (uint k = 0u; k < ITEMS; ++k) {
    uint i = begin + k * GROUP + t;
    bool live = i < u_count;
    uint key = live ? keysIn[i] : 0u;
    uint d = (key >> u_shift) & (GROUP - 1u);
    uint row = d * (GROUP / 32u);
    if (live) atomicOr(masks[row + word], bit);
    barrier();
    if (live) {
      uint rank = bitCount(masks[row + word] & (bit - 1u));
      for (uint w = 0u; w < word; ++w) rank += bitCount(masks[row + w]);
      uint at = offsets[d] + rank;
      keysOut[at] = key;
      valuesOut[at] = valuesIn[i];
      atomicAdd(added[d], 1u);
    }
    barrier();
    if (live) masks[row + word] = 0u;
    offsets[t] += added[t];
    added[t] = 0u;
    barrier();
  }
}
)glsl";

GLuint buildCompute(const char* name, const char* body) {
  const std::string source = commonSource() + body;
  return buildComputeProgram(name, source.c_str());
}

}  // namespace

void dispatch(GLuint groups) {
  if (groups == 0) return;
  const GLuint x = std::min(groups, kMaxGroupsX);
  const GLuint y = (groups + x - 1) / x;
  glDispatchCompute(x, y, 1);
}

bool GpuDepthSort::available() {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  return (major > 4 || (major == 4 && minor >= 3)) && glDispatchCompute != nullptr &&
         glMemoryBarrier != nullptr;
}

void GpuDepthSort::create() {
  if (keysProgram_ != 0) return;
  keysProgram_ = buildCompute("depth sort keys", kKeysShader);
  histogramProgram_ = buildCompute("depth sort histogram", kHistogramShader);
  scanProgram_ = buildCompute("depth sort scan", kScanShader);
  scatterProgram_ = buildCompute("depth sort scatter", kScatterShader);
  glGenBuffers(2, keys_);
  glGenBuffers(2, values_);
  glGenBuffers(1, &counts_);
}

void GpuDepthSort::reserve(std::size_t count) {
  if (count <= capacity_) return;
  const auto bytes = static_cast<GLsizeiptr>(count * sizeof(std::uint32_t));
  for (int i = 0; i < 2; ++i) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, keys_[i]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_COPY);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, values_[i]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_COPY);
  }
  const std::size_t blocks = (count + kBlock - 1) / kBlock;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, counts_);
  glBufferData(GL_SHADER_STORAGE_BUFFER,
               static_cast<GLsizeiptr>(blocks * kGroup * sizeof(std::uint32_t)), nullptr,
               GL_DYNAMIC_COPY);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  capacity_ = count;
}

void GpuDepthSort::sort(GLuint splatTexture, std::size_t count, const glm::mat4& modelView,
                        GLuint subset) {
  create();
  count = std::min<std::size_t>(count, kMaxSplats);
  if (count == 0) return;
  reserve(count);
  const auto n = static_cast<GLuint>(count);
  const GLuint blocks = (n + kBlock - 1) / kBlock;

  glUseProgram(keysProgram_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, splatTexture);
  glUniform1i(uniform(keysProgram_, "u_splats"), 0);
  glUniform4f(uniform(keysProgram_, "u_row"), modelView[0][2], modelView[1][2], modelView[2][2],
              modelView[3][2]);
  glUniform1ui(uniform(keysProgram_, "u_count"), n);
  glUniform1i(uniform(keysProgram_, "u_subset"), subset != 0 ? 1 : 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, keys_[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, values_[0]);
  // (Without a subset the binding holds a buffer the shader does not read.)
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, subset != 0 ? subset : keys_[1]);
  dispatch((n + kGroup - 1) / kGroup);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, counts_);
  for (int pass = 0; pass < 4; ++pass) {
    const int in = pass % 2, out = 1 - in;
    const auto shift = static_cast<GLuint>(8 * pass);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, keys_[in]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, values_[in]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, keys_[out]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, values_[out]);

    glUseProgram(histogramProgram_);
    glUniform1ui(uniform(histogramProgram_, "u_count"), n);
    glUniform1ui(uniform(histogramProgram_, "u_shift"), shift);
    glUniform1ui(uniform(histogramProgram_, "u_blocks"), blocks);
    dispatch(blocks);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    glUseProgram(scanProgram_);
    glUniform1ui(uniform(scanProgram_, "u_length"), blocks * kGroup);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    glUseProgram(scatterProgram_);
    glUniform1ui(uniform(scatterProgram_, "u_count"), n);
    glUniform1ui(uniform(scatterProgram_, "u_shift"), shift);
    glUniform1ui(uniform(scatterProgram_, "u_blocks"), blocks);
    dispatch(blocks);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  // Four passes end where they began: the order is in values_[0].
  for (GLuint b = 0; b < 6; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
  glUseProgram(0);
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GpuDepthSort::release() {
  if (keysProgram_ == 0) return;
  for (GLuint p : {keysProgram_, histogramProgram_, scanProgram_, scatterProgram_})
    glDeleteProgram(p);
  glDeleteBuffers(2, keys_);
  glDeleteBuffers(2, values_);
  glDeleteBuffers(1, &counts_);
  keysProgram_ = histogramProgram_ = scanProgram_ = scatterProgram_ = 0;
  keys_[0] = keys_[1] = values_[0] = values_[1] = counts_ = 0;
  capacity_ = 0;
}

}  // namespace gs::render::detail
