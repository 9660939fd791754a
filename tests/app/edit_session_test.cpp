// The viewer's edit session chooses refit or rebuild like `glint render --edits`: it refits
// the shown tracer in place only when the Gaussian count stays and nobody else holds the
// shown scene, and the tracer it keeps traces the edited scene as a fresh build does.
#include "app/viewer/edit_session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "common/random_gaussians.h"
#include "edit/gaussian_edits.h"
#include "render/gaussian_layers.h"

namespace glint {
namespace {

nlohmann::json editOf(const char* operation) {
  return {{"selection", "everything"}, {"operation", nlohmann::json::parse(operation)}};
}

TEST(EditSession, RefitsInPlaceOnlyWhenTheCountStaysAndTheSceneIsFree) {
  const GaussianScene pristine = randomScene(400, 5);
  EditSession session(pristine, TraceSettings{}, kDefaultMaxGaussians);
  int released = 0;
  TracerUpdateContext context;
  context.probeCamera =
      Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0, 0, 4), Vec3d(0, 0, 0), Vec3d(0, 1, 0)), 0.9, 32, 24);
  context.workRays = 1;  // almost nothing to trace: the cheaper update wins, the refit
  context.releaseShown = [&] { ++released; };

  // A request still reading the shown scene: it must not change under it, so no refit.
  std::shared_ptr<const TracedScene> held = session.current();
  session.apply(editOf(R"({"op": "translate", "offset": [0.25, 0, 0]})"), context);
  nlohmann::json update = session.status()["tracer_update"];
  EXPECT_EQ(released, 1);
  EXPECT_FALSE(update["refit_possible"].get<bool>());
  EXPECT_EQ(update["action"], "rebuild");
  EXPECT_EQ(update["no_refit"], "the shown scene was in use");
  EXPECT_EQ(held->scene->position[7], pristine.position[7]);
  EXPECT_EQ(session.current()->scene->position[7].x, pristine.position[7].x + 0.25f);
  held.reset();

  // Same count, nobody else holding the scene: refitted in place.
  session.apply(editOf(R"({"op": "roughness", "set": 0.9})"), context);
  update = session.status()["tracer_update"];
  EXPECT_EQ(released, 2);
  EXPECT_TRUE(update["refit_possible"].get<bool>());
  EXPECT_EQ(update["action"], "refit") << update;
  std::shared_ptr<const TracedScene> shown = session.current();
  EXPECT_EQ(shown->scene->roughness[3], 0.9f);
  EXPECT_EQ(shown->scene->position[7].x, pristine.position[7].x + 0.25f);
  // The refitted structure traces the edited scene exactly as one built on it.
  std::unique_ptr<GaussianTracer> fresh = makeGaussianTracer(viewerTracer());
  fresh->build(*shown->scene, TraceSettings{});
  Rng rng(11);
  for (int i = 0; i < 200; ++i) {
    TraceRay ray{Vec3f(0, 0, 4) + randomDirection(rng) * 0.5f, Vec3f(0), 0.0f};
    ray.direction = normalize(Vec3f(uniform(rng, -1, 1), uniform(rng, -1, 1), 0) - ray.origin);
    RayResult a = shown->tracer->trace(ray), b = fresh->trace(ray);
    ASSERT_EQ(a.diffuse, b.diffuse) << i;
    ASSERT_EQ(a.depth, b.depth) << i;
    ASSERT_EQ(a.roughness, b.roughness) << i;
  }
  shown.reset();

  // A duplicate changes the count: rebuilt, and the renderer is never asked to let go.
  session.apply(editOf(R"({"op": "duplicate", "offset": [0, 1, 0]})"), context);
  update = session.status()["tracer_update"];
  EXPECT_EQ(released, 2);
  EXPECT_FALSE(update["refit_possible"].get<bool>());
  EXPECT_EQ(update["no_refit"], "the Gaussian count changed");
  EXPECT_EQ(session.status()["gaussians"], 800);
  // Undo returns to 400 Gaussians (rebuilt), then undoing the roughness keeps the count.
  session.undo(context);
  session.undo(context);
  EXPECT_EQ(released, 3);
  EXPECT_EQ(session.status()["tracer_update"]["action"], "refit");
  EXPECT_EQ(session.current()->scene->roughness[3], pristine.roughness[3]);
}


// The camera and work of the plate room's sessions, and the request that moves its plate
// sideways (uncovering the floor's shadow under it).
TracerUpdateContext plateRoomContext() {
  TracerUpdateContext context;
  context.probeCamera =
      Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0, -3, 1), Vec3d(0, 0, 0), Vec3d(0, 0, 1)), 0.9, 32, 24);
  context.workRays = 1e6;
  return context;
}

nlohmann::json plateMove() {
  return {{"selection", {{"box", {{"min", {-0.2, -0.2, 0.3}}, {"max", {0.2, 0.2, 0.5}}}}}},
          {"operation", {{"op", "translate"}, {"offset", {0.6, 0.0, 0.0}}}}};
}

// With relighting, deleting a plate that shades a floor brightens the floor under it; undo
// returns every colour to the pristine scene's exactly.
TEST(EditSession, RelightsAfterEachEditAndUndoRestoresThePristineColours) {
  const test::PlateRoom room = test::plateRoom();
  const GaussianScene& pristine = room.scene;
  EditSession session(pristine, TraceSettings{}, kDefaultMaxGaussians, RelightSettings{});
  const TracerUpdateContext context = plateRoomContext();

  session.apply({{"selection", {{"box", {{"min", {-0.2, -0.2, 0.3}}, {"max", {0.2, 0.2, 0.5}}}}}},
                 {"operation", {{"op", "delete"}}}},
                context);
  nlohmann::json status = session.status();
  ASSERT_TRUE(status.contains("relight")) << status;
  EXPECT_GE(status["relight_ms"].get<double>(), 0.0);
  std::shared_ptr<const TracedScene> shown = session.current();
  ASSERT_EQ(shown->scene->size(), room.floorEnd);
  const size_t centre = room.centre;
  EXPECT_GT(shown->scene->diffuse[centre].x, 1.15f * pristine.diffuse[centre].x);
  // The shown tracer sees the relit colours (it was refitted after relighting).
  TraceRay down{pristine.position[centre] + Vec3f(0, 0, 0.3f), Vec3f(0, 0, -1), 0.0f};
  EXPECT_GT(shown->tracer->trace(down).diffuse.x, 1.1f * pristine.diffuse[centre].x);
  shown.reset();

  session.undo(context);
  shown = session.current();
  ASSERT_EQ(shown->scene->size(), pristine.size());
  for (size_t i = 0; i < pristine.size(); ++i) ASSERT_EQ(shown->scene->diffuse[i], pristine.diffuse[i]) << i;
}


// The plate moved sideways in a session that relights at once: what a deferred session
// must end up showing.
class PlateMove : public ::testing::Test {
 protected:
  PlateMove() { immediate.apply(move, context); }
  const test::PlateRoom room = test::plateRoom();
  const GaussianScene& pristine = room.scene;
  const TracerUpdateContext context = plateRoomContext();
  const nlohmann::json move = plateMove();
  EditSession immediate{pristine, TraceSettings{}, kDefaultMaxGaussians, RelightSettings{}};
};

// Deferred (the viewer's way): the edit is shown unrelit with "relight_pending", and
// relight() then gives exactly the colours an immediate session shows, in a tracer that
// traces them; with the renderer still holding the scene, a new tracer is built instead.
TEST_F(PlateMove, DeferredRelightingShowsTheEditFirstThenTheImmediateColours) {
  EXPECT_FALSE(immediate.status()["relight_pending"].get<bool>());

  for (bool rendererHolds : {false, true}) {
    EditSession deferred(pristine, TraceSettings{}, kDefaultMaxGaussians, RelightSettings{}, std::nullopt, true);
    deferred.apply(move, context);
    nlohmann::json status = deferred.status();
    EXPECT_TRUE(status["relight_pending"].get<bool>()) << status;
    std::shared_ptr<const TracedScene> shown = deferred.current();
    EXPECT_EQ(shown->scene->diffuse[room.centre], pristine.diffuse[room.centre]);  // not relit yet
    const GaussianScene* shownScene = shown->scene.get();
    if (!rendererHolds) shown.reset();

    std::shared_ptr<const TracedScene> relit = deferred.relight(context);
    status = deferred.status();
    EXPECT_FALSE(status["relight_pending"].get<bool>());
    EXPECT_NE(status["relight"].get<std::string>().find("relit"), std::string::npos) << status;
    const GaussianScene& expected = *immediate.current()->scene;
    ASSERT_EQ(relit->scene->size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(relit->scene->diffuse[i], expected.diffuse[i]) << i;
    EXPECT_NE(relit->scene->diffuse[room.centre], pristine.diffuse[room.centre]);  // the old shadow brightened
    // Refitted in place when nobody held the shown scene, else traced by a new tracer;
    // either way the tracer shown traces the relit colours.
    EXPECT_EQ(relit->scene.get() == shownScene, !rendererHolds);
    if (rendererHolds) {
      EXPECT_EQ(shown->scene->diffuse[room.centre], pristine.diffuse[room.centre]);  // untouched
    }
    TraceRay down{pristine.position[room.centre] + Vec3f(0, 0, 0.3f), Vec3f(0, 0, -1), 0.0f};
    EXPECT_EQ(relit->tracer->trace(down).diffuse, immediate.current()->tracer->trace(down).diffuse);
    // Nothing waits now: a second call changes nothing.
    EXPECT_EQ(deferred.relight(context), relit);
  }
}


// A preview shows relit colours over a tracer of its own while the relighting stays
// pending; the full relighting after it still gives exactly the immediate session's colours
// (it traces the unrelit scene the preview kept, not the preview's colours).
TEST_F(PlateMove, PreviewThenFullRelightingGivesTheImmediateColours) {

  EditSession deferred(pristine, TraceSettings{}, kDefaultMaxGaussians, RelightSettings{}, std::nullopt, true);
  EXPECT_EQ(deferred.relightPreview(), deferred.current());  // nothing waits
  deferred.apply(move, context);
  const std::shared_ptr<const TracedScene> unrelit = deferred.current();
  std::shared_ptr<const TracedScene> preview = deferred.relightPreview();
  nlohmann::json status = deferred.status();
  EXPECT_TRUE(status["relight_pending"].get<bool>()) << status;
  EXPECT_TRUE(status["relight_preview"].get<bool>()) << status;
  EXPECT_EQ(status["relight"].get<std::string>().rfind("preview: relit", 0), 0u) << status;
  EXPECT_NE(preview, unrelit);
  EXPECT_GT(preview->scene->diffuse[room.centre].x, 1.1f * pristine.diffuse[room.centre].x);
  EXPECT_EQ(unrelit->scene->diffuse[room.centre], pristine.diffuse[room.centre]);  // kept as it was
  TraceRay down{pristine.position[room.centre] + Vec3f(0, 0, 0.3f), Vec3f(0, 0, -1), 0.0f};
  EXPECT_GT(preview->tracer->trace(down).diffuse.x, 1.1f * pristine.diffuse[room.centre].x);
  EXPECT_EQ(deferred.relightPreview(), preview);  // shown already

  const GaussianScene* previewScene = preview->scene.get();
  preview.reset();  // the renderer lets go: the preview's scene is refitted in place
  std::shared_ptr<const TracedScene> relit = deferred.relight(context);
  status = deferred.status();
  EXPECT_FALSE(status["relight_pending"].get<bool>());
  EXPECT_FALSE(status["relight_preview"].get<bool>());
  EXPECT_EQ(relit->scene.get(), previewScene);
  const GaussianScene& expected = *immediate.current()->scene;
  ASSERT_EQ(relit->scene->size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(relit->scene->diffuse[i], expected.diffuse[i]) << i;
  EXPECT_EQ(relit->tracer->trace(down).diffuse, immediate.current()->tracer->trace(down).diffuse);
}


// An edit that arrives while a deferred relighting runs cancels it rather than waiting for
// it; whichever happens first, the session ends consistent: undone to the pristine colours,
// nothing pending, and the relighting request answered without an error.
TEST(EditSession, AnEditDuringADeferredRelightingCancelsIt) {
  const test::PlateRoom room = test::plateRoom();
  const GaussianScene& pristine = room.scene;
  const TracerUpdateContext context = plateRoomContext();
  RelightSettings slow;
  slow.setRays(65536);  // about 8 s of tracing here, uncancelled
  EditSession session(pristine, TraceSettings{}, kDefaultMaxGaussians, slow, std::nullopt, true);
  session.apply(plateMove(), context);
  ASSERT_TRUE(session.status()["relight_pending"].get<bool>());
  std::shared_ptr<const TracedScene> answered;
  std::thread relighting([&] { answered = session.relight(context); });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto started = std::chrono::steady_clock::now();
  session.undo(context);
  const double undoSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  relighting.join();
  ASSERT_TRUE(answered);
  // Cancelled (or, had the undo come first, found nothing waiting): no relit colour was shown.
  EXPECT_EQ(answered->scene->diffuse[room.centre], pristine.diffuse[room.centre]);
  const nlohmann::json status = session.status();
  EXPECT_FALSE(status["relight_pending"].get<bool>()) << status;
  EXPECT_EQ(status["operations"], 0);
  std::shared_ptr<const TracedScene> shown = session.current();
  for (size_t i = 0; i < pristine.size(); ++i) ASSERT_EQ(shown->scene->diffuse[i], pristine.diffuse[i]) << i;
  // Seconds of tracing left, not waited for (a loose bound: the point is not to wait them).
  EXPECT_LT(undoSeconds, 2.0);
}

// The deferred relighting traces without the session's lock: the page's status polls,
// selection previews, the edit document and an export answer at once while it runs, and a
// relighting that no edit interrupted is shown when it ends.
TEST(EditSession, AnswersWhileADeferredRelightingRuns) {
  const test::PlateRoom room = test::plateRoom();
  const GaussianScene& pristine = room.scene;
  const TracerUpdateContext context = plateRoomContext();
  RelightSettings slow;
  slow.setRays(8192);  // about a second of tracing here
  EditSession session(pristine, TraceSettings{}, kDefaultMaxGaussians, slow, std::nullopt, true);
  session.apply(plateMove(), context);
  std::shared_ptr<const TracedScene> answered;
  double relightSeconds = 0;
  std::thread relighting([&] {
    const auto started = std::chrono::steady_clock::now();
    answered = session.relight(context);
    relightSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto started = std::chrono::steady_clock::now();
  const nlohmann::json status = session.status();
  const nlohmann::json everything = {{"box", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
  const nlohmann::json histogram = session.preview({{"selection", everything}, {"attribute", "roughness"}});
  const EditDocument document = session.document();
  const double answerSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  relighting.join();
  EXPECT_TRUE(status["relight_pending"].get<bool>()) << status;
  EXPECT_GT(histogram["count"].get<int64_t>(), 0);
  EXPECT_EQ(document.operations.size(), 1u);
  // Answered while the relighting still ran (it traced for relightSeconds).
  EXPECT_LT(answerSeconds, 0.5 * relightSeconds) << answerSeconds << " " << relightSeconds;
  ASSERT_TRUE(answered);
  EXPECT_GT(answered->scene->diffuse[room.centre].x, 1.1f * pristine.diffuse[room.centre].x);  // shown relit
  EXPECT_FALSE(session.status()["relight_pending"].get<bool>());
}

}  // namespace
}  // namespace glint
