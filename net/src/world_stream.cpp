#include "net/streams.hpp"

#include <algorithm>

namespace gs::net {

WorldStream::WorldStream(FetchRequest request, vrml::ParseOptions parse)
    : parser_(std::make_shared<vrml::StreamingParser>(request.url, std::move(parse))) {
  progress_.url = request.url;
  progress_.kind = StreamKind::world;
  scene_ = std::shared_ptr<const vrml::Scene>(parser_, &parser_->scene());
  transfer_ = startTransfer(std::move(request));
}

WorldStream::~WorldStream() = default;

bool WorldStream::pumpWaiting() {
  const bool grew = parser_->feed({}) > 0;  // retries the statement that waits
  progress_.rootNodes = parser_->scene().rootNodes.size();
  if (parser_->waitingForExternProto()) return grew;
  parser_->finish();
  progress_.rootNodes = parser_->scene().rootNodes.size();
  progress_.state = *endWhenArrived_;
  endWhenArrived_.reset();
  return true;
}

bool WorldStream::pump(Allowance& allowance) {
  if (!transfer_) return endWhenArrived_ ? pumpWaiting() : false;
  chunk_.clear();
  transfer_->take(chunk_);
  bool changed = false;
  if (chunk_.empty() && parser_->waitingForExternProto()) {
    changed = parser_->feed({}) > 0;  // retries the statement that waits
    progress_.rootNodes = parser_->scene().rootNodes.size();
  }
  if (!chunk_.empty()) {
    if (progress_.bytes == 0) {
      // Relative URLs inside resolve against where the bytes came from, after redirects.
      const std::string effective = transfer_->status().effectiveUrl;
      if (!effective.empty() && effective != progress_.url) parser_->rebase(effective);
    }
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::uint64_t>(chunk_.size(), allowance.remaining));
    allowance.remaining -= n;
    progress_.bytes += n;
    progress_.state = StreamState::loading;
    changed = parser_->feed(std::string_view(chunk_).substr(0, n)) > 0;
    progress_.rootNodes = parser_->scene().rootNodes.size();
    if (n < chunk_.size() || allowance.remaining == 0) {
      stop("stopped after " + std::to_string(progress_.bytes) + " bytes");
      return true;
    }
  }
  const TransferStatus s = transfer_->status();
  progress_.bytesPerSecond = s.bytesPerSecond;
  progress_.expectedBytes = s.resourceSize >= 0 ? s.resourceSize : s.expected;
  if (!s.finished() || s.received > progress_.bytes) return changed;  // more to take
  if (s.state == TransferState::done) {
    end(StreamState::done, {});
  } else if (s.state == TransferState::cancelled) {
    end(StreamState::stopped, progress_.url + ": cancelled");
  } else {
    end(StreamState::failed, s.error);
  }
  return true;
}

void WorldStream::stop(const std::string& why) {
  if (!transfer_ && endWhenArrived_) {  // all bytes in, a statement waiting: end it now
    endWhenArrived_.reset();
    parser_->finish();  // the EXTERNPROTO still on its way fails with a warning
    progress_.rootNodes = parser_->scene().rootNodes.size();
    progress_.state = StreamState::stopped;
    progress_.error = why;
    return;
  }
  if (!transfer_) return;
  transfer_->cancel();
  end(StreamState::stopped, why);
}

void WorldStream::abandon(const std::string& why) {
  if (!transfer_ && !endWhenArrived_) return;  // ended already
  if (transfer_) transfer_->cancel();
  transfer_.reset();
  endWhenArrived_.reset();
  progress_.rootNodes = parser_->scene().rootNodes.size();
  progress_.state = StreamState::stopped;
  progress_.error = why;
}

void WorldStream::end(StreamState state, const std::string& message) {
  transfer_.reset();
  if (state == StreamState::done && parser_->waitingForExternProto()) {
    endWhenArrived_ = state;  // ends in pumpWaiting() once the EXTERNPROTO file answered
    progress_.error = message;
    return;
  }
  // A transfer that failed before its first byte has no text to diagnose.
  if (progress_.bytes > 0 || state == StreamState::done) parser_->finish();
  progress_.rootNodes = parser_->scene().rootNodes.size();
  progress_.state = state;
  progress_.error = message;
}

}  // namespace gs::net
