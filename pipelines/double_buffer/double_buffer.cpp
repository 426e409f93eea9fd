// Conventional double buffering: render with the newest pose, swap at the next
// retrace after completion; optionally render ahead with N frames queued, or
// swap at once without vsync (tearing).
#include <deque>
#include <memory>

#include "latsim/pipelines/double_buffer.hpp"
#include "latsim/pipelines/double_buffer_analytic.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/render_cost.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/tracker/config.hpp"

namespace latsim::pipelines {

namespace {

/// Renders frames back to back on one renderer and hands them to the display.
class DoubleBufferPipeline final : public Pipeline {
 public:
  std::string name() const override { return "double_buffer"; }

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    const auto& p = ctx.pipeline;
    vsync_ = p.boolean("vsync", true);
    queued_frames_ = static_cast<int>(p.integer("queued_frames", 0, 0, 16));
    const auto render = p.child("render");
    std::optional<scenario::ConfigNode> scene = ctx.root.optional_child("scene");
    cost_ = RenderCost::from_config(render, scene ? &*scene : nullptr, ctx.display.timing().params().width_px,
                                    ctx.display.timing().params().height_px, ctx.display.eyes());
    if (!vsync_ && cost_.nominal_frame_time() == des::Time::zero())
      p.fail("vsync", "without vsync the renderer runs back to back, so frames need a render time above zero");
    stream_ = std::make_unique<des::RandomStream>(ctx.stream("renderer"));
    kind_frame_ = ctx.sim.kind("renderer.frame");
    if (vsync_) ctx.display.on_retrace([this](int64_t field, des::Time t) { retrace(field, t); });
    begin_frame();
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    figures["frames_rendered"] = frames_done_;
    figures["missed_refreshes"] = missed_refreshes_;
    figures["nominal_frame_time_ms"] = cost_.nominal_frame_time().to_ms();
    if (vsync_ && queued_frames_ == 0 && !cost_.varies()) {
      // The same models, rebuilt from the scenario, but asked for phases only.
      const auto tracker = tracker::parse_tracker(ctx.root.child("tracker"));
      std::unique_ptr<tracker::Transport> link = ctx.root.has("transport")
                                                     ? tracker::make_transport(ctx.root.child("transport"))
                                                     : std::make_unique<tracker::DirectLink>();
      if (auto a = analytic_double_buffer(ctx.display.timing(), tracker, *link, cost_.nominal_frame_time()))
        figures["analytic"] = *a;
    }
  }

 private:
  struct Done {
    std::vector<int64_t> ids;
    int64_t frame;
    des::Time render_end;
  };

  void begin_frame() {
    const auto sample = ctx_->host.newest_at(ctx_->sim.now());
    if (!sample) {
      waiting_for_pose_ = true;  // retried at the next retrace
      if (!vsync_) ctx_->sim.after(des::Time::ms(1), kind_frame_, [this] { begin_frame(); });
      return;
    }
    waiting_for_pose_ = false;
    busy_ = true;
    const des::Time start = ctx_->sim.now();
    const des::Time end = start + cost_.frame_time(*stream_);
    const tracker::TrackerSample s = *sample;
    ctx_->sim.at(end, kind_frame_, [this, s, start] { complete(s, start); });
  }

  void complete(const tracker::TrackerSample& s, des::Time start) {
    busy_ = false;
    const des::Time now = ctx_->sim.now();
    Done done{{}, frame_, now};
    for (int eye = 0; eye < ctx_->display.eyes(); ++eye) {
      ImageRecord rec = ctx_->image_record(frame_, eye, s, start, now);
      done.ids.push_back(ctx_->recorder.register_image(rec));
    }
    if (ctx_->timeline) ctx_->timeline->add("RENDER", frame_, -1, "renderer", start, now);
    ++frame_;
    ++frames_done_;
    if (!vsync_) {
      // No vsync: the new image replaces the front buffer mid-scan.
      for (int eye = 0; eye < ctx_->display.eyes(); ++eye) ctx_->display.present_now(eye, done.ids[eye]);
      begin_frame();
      return;
    }
    queue_.push_back(std::move(done));
    if (static_cast<int>(queue_.size()) <= queued_frames_) begin_frame();
  }

  void retrace(int64_t, des::Time now) {
    if (queue_.empty()) {
      if (shown_any_) ++missed_refreshes_;
    } else {
      const Done d = std::move(queue_.front());
      queue_.pop_front();
      // Called at the retrace before scanout: the swap takes effect for this field.
      for (int eye = 0; eye < ctx_->display.eyes(); ++eye) ctx_->display.present_now(eye, d.ids[eye]);
      if (ctx_->timeline) ctx_->timeline->add("QUEUED", d.frame, -1, "swapchain", d.render_end, now);
      shown_any_ = true;
    }
    if (!busy_ && (waiting_for_pose_ || static_cast<int>(queue_.size()) <= queued_frames_)) begin_frame();
  }

  RunContext* ctx_ = nullptr;
  bool vsync_ = true;
  int queued_frames_ = 0;
  RenderCost cost_;
  std::unique_ptr<des::RandomStream> stream_;
  des::KindId kind_frame_ = 0;
  std::deque<Done> queue_;
  bool busy_ = false;
  bool waiting_for_pose_ = false;
  bool shown_any_ = false;
  int64_t frame_ = 0;
  int64_t frames_done_ = 0;
  int64_t missed_refreshes_ = 0;
};

}  // namespace

std::unique_ptr<Pipeline> make_double_buffer_pipeline() { return std::make_unique<DoubleBufferPipeline>(); }

}  // namespace latsim::pipelines
