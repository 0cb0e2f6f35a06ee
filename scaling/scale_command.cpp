#include "scaling/scale_command.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <filesystem>

#include "core/error.hpp"
#include "core/timers.hpp"
#include "scaling/scale_report.hpp"
#include "scaling/scale_runs.hpp"
#include "scaling/scale_study.hpp"

namespace cgdem::scaling {

namespace fs = std::filesystem;

ScaleCommand::ScaleCommand(CLI::App& app)
    : sub_(app.add_subcommand("scale", "coarse-grain consistency: the same case at several ratios l")) {
  std::string th_help = "agreement threshold name=value (repeatable); defaults:";
  for (const auto& t : default_thresholds()) th_help += fmt::format(" {}={:g}", t.name, t.value);
  sub_->add_option("case", case_file_, "case file (TOML)")->required()->check(CLI::ExistingFile);
  sub_->add_option("--ratios", ratios_, "coarse-grain ratios, must include 1 (default 1,2,3)")->delimiter(',');
  sub_->add_option("--simply-large", simply_large_, "also run the simply-large system: d_original x L, ratio 1");
  sub_->add_option("--output", output_, "report folder (default: out/scale_<case name>)");
  sub_->add_option("--set", sets_, "override a key of every run: key.path=value (repeatable)");
  sub_->add_option("--threshold", thresholds_, th_help);
  sub_->add_flag("--report-only", report_only_, "analyse the runs already in the report folder, run nothing");
  sub_->add_flag("--no-plots", no_plots_, "do not call scaling/plot_scale.py");
  sub_->add_option("--pod-dx", pod_dx_, "cell size (m) of the solid fraction for POD in vacuum (default 2 x largest parcel)")
      ->check(CLI::PositiveNumber);
  sub_->add_option("--from", from_, "analysis start time, s (default: 0 when the case starts before 0 with "
                                    "settling, else time.start)");
  sub_->add_option("--threads", threads_, "OpenMP threads of each run")->check(CLI::PositiveNumber);
}

int ScaleCommand::run() const {
  if (threads_ > 0) omp_set_num_threads(threads_);
  Thresholds th;
  for (const auto& t : thresholds_) th.set(t);
  const std::string report = output_.empty() ? "out/scale_" + fs::path(case_file_).stem().string() : output_;
  const auto plans = plan_runs(ratios_, simply_large_, report);
  fs::create_directories(report);
  std::vector<StudyInfo> infos;
  for (const auto& p : plans) {
    write_derived_case(case_file_, p);
    infos.push_back(read_study_info(p.case_file, sets_, fs::absolute(p.dir).string()));
  }
  ReportContext ctx;
  ctx.dir = report;
  ctx.base_case = case_file_;
  ctx.command = fmt::format("cgdem scale {} --ratios {}{}{}{}", case_file_, fmt::join(ratios_, ","),
                            simply_large_ > 0 ? fmt::format(" --simply-large {:g}", simply_large_) : "",
                            sets_.empty() ? "" : " --set " + fmt::format("{}", fmt::join(sets_, " --set ")),
                            thresholds_.empty() ? "" : " --threshold " + fmt::format("{}", fmt::join(thresholds_, " --threshold ")));
  for (size_t i = 0; i < plans.size(); ++i) {
    std::string why;
    if (report_only_) {
      ctx.run_notes.push_back(finished_run(plans[i], infos[i], &why) ? "finished (report only)" : "as found: " + why);
      continue;
    }
    Stopwatch clock;
    const bool ran = run_or_pick_up(plans[i], sets_, infos[i]);
    const double wall = clock.seconds();
    ctx.run_notes.push_back(ran ? fmt::format("ran in {:.1f} s", wall) : "picked up");
    if (ran) fmt::print("cgdem scale: {} ran in {:.1f} s (wall)\n", plans[i].label, wall);
  }
  Stopwatch clock;
  PodOptions pod;
  pod.dx = pod_dx_;
  const StudyInfo& info = infos[0];
  double t0 = std::isnan(from_) ? (info.t_start < 0 && info.t_end > 0 ? 0.0 : info.t_start) : from_;
  if (!(t0 >= info.t_start && t0 < info.t_end))
    throw Error(fmt::format("--from {:g}: must lie in [time.start, time.end) = [{:g}, {:g}) s", t0, info.t_start,
                            info.t_end));
  fmt::print("cgdem scale: analysing from t = {:g} s\n", t0);
  const Study s = analyse_study(plans, info, t0, th, pod);
  const std::string md = write_report(s, ctx);
  print_verdicts(s);
  if (!no_plots_) draw_plots(report);
  fmt::print("cgdem scale: analysis {:.1f} s; report {}\n", clock.seconds(), md);
  return 0;
}

}  // namespace cgdem::scaling
