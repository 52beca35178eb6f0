// The one routing of document commands (server/document/document_dispatch.h):
// every command of an open document reaches the endpoint call that serves
// it, with its client_seq and session; anything else is left to the caller.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "server/document/document_dispatch.h"
#include "support/decoding_inbox.h"

namespace tessera::server {
namespace {

// Records which call each dispatch made, as "call seq".
class RecordingEndpoint final : public DocumentEndpoint {
 public:
  void join(std::shared_ptr<Subscriber>, std::string, wire::Role) override { calls.push_back("join"); }
  void leave(uint64_t) override { calls.push_back("leave"); }
  void select(std::shared_ptr<Subscriber>, uint64_t seq, wire::Selection) override {
    calls.push_back("select " + std::to_string(seq));
  }
  void resendPresence(uint64_t) override { calls.push_back("resendPresence"); }
  void subscribe(std::shared_ptr<Subscriber>, const wire::Subscribe& request, uint64_t seq,
                 bool resync) override {
    calls.push_back("subscribe " + std::to_string(seq) + (resync ? " resync" : "") +
                    (request.with_commands() ? " with_commands" : "") + " max " +
                    std::to_string(request.profile().max_level()) + (request.has_view() ? " view" : ""));
  }
  void setView(std::shared_ptr<Subscriber>, uint64_t seq, wire::View view) override {
    calls.push_back("setView " + std::to_string(seq) + " width " + std::to_string(view.width()));
  }
  void unsubscribe(uint64_t session) override { calls.push_back("unsubscribe " + std::to_string(session)); }
  void command(std::shared_ptr<Subscriber>, std::string author, wire::ClientMessage message) override {
    calls.push_back("command " + std::to_string(message.client_seq()) + " by " + author);
  }
  void exportGlb(std::shared_ptr<Subscriber>, uint64_t seq, wire::ExportDocument) override {
    calls.push_back("export " + std::to_string(seq));
  }
  void morphControl(std::shared_ptr<Subscriber>, uint64_t seq, wire::GetMorphControl) override {
    calls.push_back("morphControl " + std::to_string(seq));
  }
  void cage(std::shared_ptr<Subscriber>, uint64_t seq, wire::GetCage request) override {
    calls.push_back("cage " + std::to_string(seq) + " level " + std::to_string(request.level()));
  }
  std::vector<std::string> calls;
};

TEST(DocumentDispatch, EachCommandReachesItsCall) {
  RecordingEndpoint endpoint;
  auto who = std::make_shared<testing::DecodingInbox>(12);
  auto send = [&](wire::ClientMessage m, uint64_t seq) {
    m.set_client_seq(seq);
    return dispatchToDocument(endpoint, who, "ann", std::move(m));
  };
  wire::ClientMessage m;
  m.mutable_subscribe()->mutable_profile()->set_max_level(3);
  m.mutable_subscribe()->set_with_commands(true);
  EXPECT_TRUE(send(m, 1));
  m.Clear();
  m.mutable_unsubscribe();
  EXPECT_TRUE(send(m, 2));
  m.Clear();
  m.mutable_select();
  EXPECT_TRUE(send(m, 3));
  m.Clear();
  m.mutable_export_document();
  EXPECT_TRUE(send(m, 4));
  m.Clear();
  m.mutable_get_morph_control();
  EXPECT_TRUE(send(m, 5));
  m.Clear();
  m.mutable_edit_batch()->add_commands()->mutable_undo()->set_edit_id(1);
  EXPECT_TRUE(send(m, 6));
  m.Clear();
  m.mutable_move_vertex();
  EXPECT_TRUE(send(m, 7));
  m.Clear();
  m.mutable_add_morph_key();
  EXPECT_TRUE(send(m, 8));
  m.Clear();
  m.mutable_set_view()->mutable_view()->set_width(390);
  EXPECT_TRUE(send(m, 11));
  m.Clear();
  m.mutable_subscribe()->mutable_view();
  EXPECT_TRUE(send(m, 12));
  m.Clear();
  m.mutable_get_cage()->set_level(2);
  EXPECT_TRUE(send(m, 13));
  m.Clear();
  m.mutable_ping();
  EXPECT_FALSE(send(m, 9)) << "not a document's command";
  m.Clear();
  m.mutable_open_document();
  EXPECT_FALSE(send(m, 10)) << "the catalogue's, not an open document's";

  EXPECT_EQ(endpoint.calls, (std::vector<std::string>{
                                "subscribe 1 with_commands max 3", "unsubscribe 12", "select 3", "export 4",
                                "morphControl 5", "command 6 by ann", "command 7 by ann", "command 8 by ann",
                                "setView 11 width 390", "subscribe 12 max 0 view", "cage 13 level 2"}));
}

TEST(DocumentDispatch, EditsAreEveryCommandThatChangesTheDocument) {
  wire::ClientMessage m;
  for (auto set : std::vector<std::function<void(wire::ClientMessage&)>>{
           [](auto& x) { x.mutable_edit_batch(); }, [](auto& x) { x.mutable_move_vertex(); },
           [](auto& x) { x.mutable_set_edge_sharpness(); }, [](auto& x) { x.mutable_set_vertex_type(); },
           [](auto& x) { x.mutable_set_interpolation(); }, [](auto& x) { x.mutable_add_morph_key(); },
           [](auto& x) { x.mutable_undo(); }, [](auto& x) { x.mutable_redo(); }}) {
    m.Clear();
    set(m);
    EXPECT_TRUE(isEditCommand(m)) << m.command_case();
  }
  for (auto set : std::vector<std::function<void(wire::ClientMessage&)>>{
           [](auto& x) { x.mutable_subscribe(); }, [](auto& x) { x.mutable_select(); },
           [](auto& x) { x.mutable_export_document(); }, [](auto& x) { x.mutable_get_morph_control(); },
           [](auto& x) { x.mutable_get_cage(); }, [](auto& x) { x.mutable_delete_document(); }}) {
    m.Clear();
    set(m);
    EXPECT_FALSE(isEditCommand(m)) << m.command_case();
  }
}

}  // namespace
}  // namespace tessera::server
