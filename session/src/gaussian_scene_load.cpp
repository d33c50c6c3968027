// A Gaussian splatting scene read in the background (gaussian_scene_load.hpp).
#include "gaussian_scene_load.hpp"

#include <chrono>
#include <new>
#include <thread>

#include "base/fetch.hpp"
#include "base/file.hpp"
#include "base/url.hpp"
#include "session/splat_inputs.hpp"
#include "splats/readers.hpp"

namespace gs::session::detail {

namespace {

/// The scene in `bytes` read (splats::readGaussians) and sorted by importance; never throws.
std::shared_ptr<const splats::GaussianCloud> decodeScene(std::string bytes, const std::string& name,
                                                         const splats::SideFileReader& sideFiles,
                                                         std::string& error) {
  try {
    splats::GaussianCloud cloud = splats::readGaussians(bytes, name, sideFiles);
    std::string().swap(bytes);  // the file's bytes go before the sorted copy is made
    return std::make_shared<const splats::GaussianCloud>(splats::sortByImportance(cloud));
  } catch (const splats::FormatError& e) {
    error = e.what();
  } catch (const std::bad_alloc&) {
    error = name + ": out of memory";
  }
  return nullptr;
}

/// `job` run on a detached thread of its own, its result in the future returned: a
/// session closed while a large scene is still being read does not wait for it (the job
/// holds only its own copies: the path or the bytes, the URL).
template <typename Job>
auto detached(Job job) {
  using Result = decltype(job());
  std::promise<Result> promise;
  auto future = promise.get_future();
  std::thread([job = std::move(job), promise = std::move(promise)]() mutable {
    promise.set_value(job());
  }).detach();
  return future;
}

bool ready(const auto& future) {
  return future.valid() && future.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

GaussianSceneLoad::GaussianSceneLoad(net::Loader& loader, std::string url, std::string referrer)
    : loader_(loader), url_(std::move(url)), referrer_(std::move(referrer)) {
  const std::string path = base::localPathOfUrl(url_);
  if (path.empty()) return;  // remote: fetched by pump()
  // Local: read, decode and sort on a thread of their own (side files from its folder or
  // below, through a fetcher of that thread's own).
  stage_ = Stage::decoding;
  decode_ = detached([path, url = url_]() -> Decoded {
    Decoded d;
    std::string bytes;
    if (!base::readFile(path, bytes, d.error, std::size_t{16} << 30)) return d;
    base::LocalFetcher fetcher;
    d.cloud = decodeScene(std::move(bytes), url, sideFileReader(fetcher, url), d.error);
    return d;
  });
}

GaussianSceneLoad::~GaussianSceneLoad() {
  cancelTree_->store(true);
}

void GaussianSceneLoad::fail(const std::string& error) {
  set_->loadError = error;
  ++set_->revision;
  stage_ = Stage::done;
}

bool GaussianSceneLoad::pump() {
  bool changed = false;
  if (stage_ == Stage::fetching) {
    std::string bytes, error;
    if (!loader_.takeInBackground(url_, referrer_, bytes, error)) {
      if (error.empty()) return false;  // on its way
      fail(error);
      return true;
    }
    stage_ = Stage::decoding;
    const splats::SplatFormat format = splats::detectSplatFormat(bytes, url_);
    if (format == splats::SplatFormat::sogMeta || format == splats::SplatFormat::gltf) {
      // Side files (SOG's images, a .gltf's buffers) come through the loader, which only
      // this thread may use: decoded here (a .glb's own buffer needs none, but which it
      // is the JSON says).
      Decoded d;
      d.cloud = decodeScene(std::move(bytes), url_, sideFileReader(loader_, url_), d.error);
      std::promise<Decoded> done;
      done.set_value(std::move(d));
      decode_ = done.get_future();
    } else {
      decode_ = detached([bytes = std::move(bytes), url = url_]() mutable {
        Decoded d;
        d.cloud = decodeScene(std::move(bytes), url, splats::SideFileReader{}, d.error);
        return d;
      });
    }
  }
  if (stage_ == Stage::decoding) {
    if (!ready(decode_)) return changed;
    Decoded d = decode_.get();
    if (!d.cloud) {
      fail(d.error);
      return true;
    }
    set_->gaussians = d.cloud;
    set_->computeBounds();
    ++set_->revision;
    changed = true;
    stage_ = Stage::tree;
    if (d.cloud->size() > 1)
      tree_ = std::async(std::launch::async, buildTreeOf, d.cloud, cancelTree_, url_);
    else
      stage_ = Stage::done;
  }
  if (stage_ == Stage::tree && ready(tree_)) {
    auto [tree, problem] = tree_.get();
    if (!problem.empty()) messages_.push_back({false, problem + ": its views draw every splat"});
    if (tree) {
      set_->lodTree = std::move(tree);
      ++set_->revision;
      changed = true;
    }
    stage_ = Stage::done;
  }
  return changed;
}

void GaussianSceneLoad::drainMessages(std::vector<std::pair<bool, std::string>>& out) {
  for (auto& m : messages_) out.push_back(std::move(m));
  messages_.clear();
}

}  // namespace gs::session::detail
