#include "server/cluster/nats_link.h"

#include <string>

namespace tessera::cluster {

namespace {

// Frees natsOptions on every return path.
struct OptionsDeleter {
  void operator()(natsOptions* o) const { natsOptions_Destroy(o); }
};

bool isNatsUrl(std::string_view url) {
  constexpr std::string_view kScheme = "nats://";
  if (url.substr(0, kScheme.size()) != kScheme) return false;
  const std::string_view rest = url.substr(kScheme.size());
  const size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos || colon == 0 || colon + 1 == rest.size()) return false;
  for (char c : rest.substr(colon + 1)) {
    if (c < '0' || c > '9') return false;
  }
  return rest.size() - colon - 1 <= 5;
}

}  // namespace

Expected<std::vector<std::string>> parseNatsUrls(std::string_view list) {
  std::vector<std::string> urls;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = list.find(',', start);
    const std::string_view url =
        list.substr(start, comma == std::string_view::npos ? list.npos : comma - start);
    if (!isNatsUrl(url)) {
      return invalidArgument("--cluster: '" + std::string(url) +
                             "' is not a NATS URL (expected nats://host:port, several separated by commas)");
    }
    urls.emplace_back(url);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return urls;
}

Expected<std::unique_ptr<NatsLink>> NatsLink::connect(const NatsLinkOptions& options) {
  std::string servers;
  for (const auto& url : options.urls) servers += (servers.empty() ? "" : ",") + url;
  auto fail = [&](natsStatus s, const char* what) {
    return ioError("NATS (" + servers + "): " + what + ": " + natsStatus_GetText(s));
  };
  if (options.urls.empty()) return invalidArgument("NATS: no server URL given");
  natsOptions* raw = nullptr;
  natsStatus s = natsOptions_Create(&raw);
  if (s != NATS_OK) return fail(s, "creating options");
  std::unique_ptr<natsOptions, OptionsDeleter> opts(raw);
  std::vector<const char*> urls;
  for (const auto& url : options.urls) urls.push_back(url.c_str());
  s = natsOptions_SetServers(opts.get(), urls.data(), static_cast<int>(urls.size()));
  if (s == NATS_OK) s = natsOptions_SetTimeout(opts.get(), options.timeout.count());
  if (s == NATS_OK && !options.clientName.empty())
    s = natsOptions_SetName(opts.get(), options.clientName.c_str());
  // Once connected, a lost server is replaced by another of the cluster for
  // as long as the process lives: reconnecting is NATS's job, and commands
  // meanwhile fail with a clear error instead of hanging.
  if (s == NATS_OK) s = natsOptions_SetMaxReconnect(opts.get(), -1);
  if (s == NATS_OK) s = natsOptions_SetReconnectWait(opts.get(), 250);
  // The link exists before the connection, so the callback has its target.
  std::unique_ptr<NatsLink> link(new NatsLink(servers, options.timeout));
  if (s == NATS_OK) s = natsOptions_SetReconnectedCB(opts.get(), &NatsLink::reconnected, link.get());
  if (s != NATS_OK) return fail(s, "setting options");
  s = natsConnection_Connect(&link->connection_, opts.get());
  if (s != NATS_OK) return fail(s, "connecting");
  jsOptions jsOpts;
  jsOptions_Init(&jsOpts);
  jsOpts.Wait = options.timeout.count();
  s = natsConnection_JetStream(&link->jetStream_, link->connection_, &jsOpts);
  if (s != NATS_OK) return fail(s, "opening JetStream");
  return link;
}

void NatsLink::onReconnected(std::function<void()> handler) {
  std::lock_guard<std::mutex> lock(handlerMutex_);
  reconnectedHandler_ = std::move(handler);
}

void NatsLink::reconnected(natsConnection*, void* self) {
  auto* link = static_cast<NatsLink*>(self);
  std::function<void()> handler;
  {
    std::lock_guard<std::mutex> lock(link->handlerMutex_);
    handler = link->reconnectedHandler_;
  }
  if (handler) handler();
}

NatsLink::~NatsLink() {
  if (jetStream_ != nullptr) jsCtx_Destroy(jetStream_);
  if (connection_ != nullptr) {
    natsConnection_Close(connection_);
    natsConnection_Destroy(connection_);
  }
}

namespace {

// JetStream's answer when the meta group or a stream has no leader, which
// is what a cluster without a majority of its servers says once it has
// noticed (JSClusterNotAvailErr). Some calls of the C client report only
// the text, with no code, so both are looked at.
bool jetStreamUnavailable(jsErrCode code) {
  if (code == JSClusterNotAvailErr) return true;
  natsStatus last = NATS_OK;
  const char* detail = nats_GetLastError(&last);
  return detail != nullptr &&
         std::string_view(detail).find("JetStream system temporarily unavailable") != std::string_view::npos;
}

}  // namespace

bool NatsLink::undecided(natsStatus status, jsErrCode code) {
  switch (status) {
    case NATS_TIMEOUT:
    case NATS_NO_RESPONDERS:
    case NATS_CONNECTION_CLOSED:
    case NATS_NOT_YET_CONNECTED:
    case NATS_CONNECTION_DISCONNECTED:
      return true;
    case NATS_OK:
      return false;
    default:
      return jetStreamUnavailable(code);
  }
}

Status NatsLink::error(natsStatus status, std::string_view what, jsErrCode code) const {
  std::string message = "NATS (" + servers_ + "): " + std::string(what) + ": " + natsStatus_GetText(status);
  if (code != 0) message += " (JetStream error " + std::to_string(static_cast<int>(code)) + ")";
  // What an operator needs to know first (docs/CLUSTER.md, "Quorum").
  if (status == NATS_NO_RESPONDERS || status == NATS_TIMEOUT) {
    message += "; JetStream did not answer: is a majority of the NATS servers up?";
  } else if (status != NATS_OK && jetStreamUnavailable(code)) {
    message += "; JetStream is unavailable: is a majority of the NATS servers up?";
  }
  // nats_GetLastError has the server's own words (e.g. "insufficient
  // resources" when quorum is lost), which are worth more than the status.
  natsStatus last = NATS_OK;
  const char* detail = nats_GetLastError(&last);
  if (detail != nullptr && *detail != '\0') message += std::string(" [") + detail + "]";
  if (status == NATS_TIMEOUT) return timeoutError(message);
  if (status == NATS_NO_RESPONDERS || (status != NATS_OK && jetStreamUnavailable(code))) {
    return unavailableError(message);
  }
  return ioError(message);
}

Expected<uint64_t> NatsLink::takeNext(kvStore* bucket, const std::string& key, std::string_view what) {
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    kvEntry* raw = nullptr;
    natsStatus s = kvStore_Get(&raw, bucket, key.c_str());
    KvEntryPtr entry(raw);
    uint64_t next = 1, revision = 0;
    if (s == NATS_OK) {
      next = std::stoull(std::string(kvEntry_ValueString(entry.get())));
      revision = kvEntry_Revision(entry.get());
    } else if (s != NATS_NOT_FOUND) {
      return error(s, "reading the next " + std::string(what));
    }
    const std::string after = std::to_string(next + 1);
    uint64_t newRevision = 0;
    s = revision == 0 ? kvStore_CreateString(&newRevision, bucket, key.c_str(), after.c_str())
                      : kvStore_UpdateString(&newRevision, bucket, key.c_str(), after.c_str(), revision);
    if (s == NATS_OK) return next;
  }
  return ioError("NATS (" + servers_ + "): taking a " + std::string(what) + " lost " +
                 std::to_string(kAttempts) + " races with other nodes");
}

Status NatsLink::ensureStream(const StreamSpec& spec) {
  jsStreamInfo* info = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  natsStatus s = js_GetStreamInfo(&info, jetStream_, spec.name.c_str(), nullptr, &code);
  if (s == NATS_OK) {
    jsStreamInfo_Destroy(info);
    return Status::ok();
  }
  if (s != NATS_NOT_FOUND) return error(s, "looking up stream " + spec.name, code);
  jsStreamConfig config;
  jsStreamConfig_Init(&config);
  config.Name = spec.name.c_str();
  std::vector<const char*> subjects;
  for (const auto& subject : spec.subjects) subjects.push_back(subject.c_str());
  config.Subjects = subjects.data();
  config.SubjectsLen = static_cast<int>(subjects.size());
  config.Storage = js_FileStorage;
  config.Replicas = spec.replicas;
  config.MaxMsgsPerSubject = spec.maxMsgsPerSubject;
  config.MaxMsgSize = spec.maxMessageBytes;
  config.AllowDirect = spec.allowDirect;
  s = js_AddStream(&info, jetStream_, &config, nullptr, &code);
  if (s != NATS_OK) {
    // Another node may have created it between the lookup and the add.
    jsStreamInfo* again = nullptr;
    if (js_GetStreamInfo(&again, jetStream_, spec.name.c_str(), nullptr, nullptr) == NATS_OK) {
      jsStreamInfo_Destroy(again);
      return Status::ok();
    }
    return error(s, "creating stream " + spec.name, code);
  }
  jsStreamInfo_Destroy(info);
  return Status::ok();
}

Expected<KvStorePtr> NatsLink::ensureBucket(const BucketSpec& spec) {
  TESSERA_ASSIGN_OR_RETURN(KvStorePtr created, createOrOpenBucket(spec));
  // nats.c creates buckets whose reads any replica may answer (direct
  // gets). A follower may not have applied the latest write yet, so a
  // token granted a moment ago, or a document just created, could read as
  // missing. The catalogue, tokens and leases need to read their own
  // writes: reads go to the bucket stream's leader instead.
  const std::string stream = bucketStream(spec.name);
  jsStreamInfo* info = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  natsStatus s = js_GetStreamInfo(&info, jetStream_, stream.c_str(), nullptr, &code);
  if (s != NATS_OK) return error(s, "looking up stream " + stream, code);
  const bool direct = info->Config->AllowDirect;
  if (direct) {
    info->Config->AllowDirect = false;
    jsStreamInfo* updated = nullptr;
    s = js_UpdateStream(&updated, jetStream_, info->Config, nullptr, &code);
    if (updated != nullptr) jsStreamInfo_Destroy(updated);
  }
  jsStreamInfo_Destroy(info);
  if (!direct) return created;
  if (s != NATS_OK) return error(s, "making the reads of bucket " + spec.name + " go to its leader", code);
  created.reset();  // reopened: the handle reads the stream's settings when opened
  return createOrOpenBucket(spec);
}

Expected<KvStorePtr> NatsLink::createOrOpenBucket(const BucketSpec& spec) {
  kvStore* kv = nullptr;
  natsStatus s = js_KeyValue(&kv, jetStream_, spec.name.c_str());
  if (s == NATS_OK) return KvStorePtr(kv);
  if (s != NATS_NOT_FOUND) return error(s, "opening key-value bucket " + spec.name);
  kvConfig config;
  kvConfig_Init(&config);
  config.Bucket = spec.name.c_str();
  config.History = 1;
  config.Replicas = spec.replicas;
  config.StorageType = js_FileStorage;
  // Nanoseconds (the stream's max age), whatever nats.c's documentation of
  // kvConfig suggests: 1000 there is refused as "max age needs to be >= 100ms".
  config.TTL = std::chrono::duration_cast<std::chrono::nanoseconds>(spec.ttl).count();
  config.MaxValueSize = spec.maxValueBytes;
  s = js_CreateKeyValue(&kv, jetStream_, &config);
  if (s != NATS_OK) {
    if (js_KeyValue(&kv, jetStream_, spec.name.c_str()) == NATS_OK) return KvStorePtr(kv);
    return error(s, "creating key-value bucket " + spec.name);
  }
  return KvStorePtr(kv);
}

}  // namespace tessera::cluster
