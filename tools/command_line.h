// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Command-line parsing of aniso_remesh, kept apart from main() so that it is tested (and fuzzed) alone.
// The options, the help text and the checks that concern one option or a pair of options (ranges, names,
// exclusions, requirements) are CLI11's (CLI11 2.1, Debian's libcli11-dev); what CLI11 cannot say (--domain
// square is an input while --domain plane names the domain of --input, a background size that applies to
// the square only) is checked after it.

#ifndef ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H
#define ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H

#include <Aniso_conformal/Curvature_metric.h>
#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/parameters.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace aniso_remesh {

struct Options {
  // input: exactly one of these
  std::string input, domain, image;
  bool no_repair = false;  // --input is read as it is: no repair
  // --domain with --input or --image: the parametric domain, checked against the topology
  Aniso_conformal::Parametric_domain parametric_domain = Aniso_conformal::Parametric_domain::AUTOMATIC;
  // metric
  std::string metric;       // curvature | fig6 | fig7 | isotropic (empty: from --metric-file or image)
  std::string metric_file;
  double stretch_max = 10;
  int smoothing_iterations = 10;
  int smoothing_rings = 2;
  int scale_smoothing_iterations = -1;  // -1: the library's default
  double gradation = -1;                // -1: the library's default; 0: none
  double anisotropy = -1;   // image only; default (-1) 0.1 colour, 0.2 grey
  // remeshing
  long long vertices = -1;
  long long iterations = 100;
  unsigned seed = 0;
  std::string cvt = "lbfgs";
  long long background_vertices = 0;
  double corner_angle = 30;
  double feature_angle = 60;  // sharp features: angle between face normals above which an edge is a crease
  bool no_features = false;   // --no-features: no crease (feature angle 180)
  bool keep_ragged_creases = false;  // --keep-ragged-creases: no crease component left out as noise
  bool no_feature_sizing = false;    // --no-feature-sizing: the metric not scaled where crease curves run close
  std::string curvature_sizing = "cones";  // --curvature-sizing: where the metric is scaled where the surface bends tighter than an edge
  std::string features_file;  // --features FILE: the user's crease edges and corners
  std::string planar_boundary = "automatic";
  std::string surface_optimization = "repair";
  unsigned threads = 0;
  // outputs
  std::string output, report, svg, histogram;
  bool quiet = false, help = false, version = false;
};

/// the tool's version line, printed by --version
inline const char* version_line() { return "aniso_remesh (Aniso_conformal) 0.1.0"; }

namespace detail {

// CLI11 2.1 reads integers with strtoll(s, 0, 0), so "010" would be octal and "0x10" hexadecimal. The tool
// takes decimal integers only, as it always did: this transform refuses anything else and drops leading
// zeros, so that the CLI::Range check and the conversion after it both read the decimal value.
inline CLI::Validator decimal_integer()
{
  return CLI::Validator(
    [](std::string& s) -> std::string {
      const std::size_t sign = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
      if(s.size() == sign || s.find_first_not_of("0123456789", sign) != std::string::npos)
        return "'" + s + "' is not an integer";
      const std::size_t first = std::min(s.find_first_not_of('0', sign), s.size() - 1);
      s = (s[0] == '-' ? "-" : "") + s.substr(first);
      return std::string();
    },
    "", "decimal integer");
}

// CLI11 2.1 reads floating-point values with strtold and rounds the long double to double: twice rounded,
// one decimal in 50000 ("0.002877") comes out one ulp away from strtod's correctly rounded value. Real
// options are therefore kept as text by CLI11 and converted here, with strtod, after this check.
inline bool to_double(const std::string& s, double& x)
{
  errno = 0;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0' && errno != ERANGE && std::isfinite(x);
}

// a finite real number for which `ok` holds; `requirement` completes "must be ..." in the message
inline CLI::Validator real(const std::string& requirement, std::function<bool(double)> ok)
{
  return CLI::Validator(
    [requirement, ok](std::string& s) -> std::string {
      double x = 0;
      if(!to_double(s, x)) return "'" + s + "' is not a finite number";
      if(!ok(x)) return "must be " + requirement + ", not " + s;
      return std::string();
    },
    "", "real " + requirement);
}

// a library default in the help text, as short as it reads ("1.8", not "1.800000")
inline std::string shortest(double x)
{
  std::ostringstream s;
  s << x;
  return s.str();
}

// a real option that CLI11 checks (as text, with `check`) and that is stored in `target` with strtod
inline CLI::Option* add_real(CLI::App& app, const std::string& name, double& target, const std::string& type,
                             const std::string& description, const CLI::Validator& check)
{
  return app
    .add_option_function<std::string>(
      name, [&target](const std::string& s) { to_double(s, target); }, description)
    ->type_name(type)
    ->check(check);
}

// CLI11's help with our usage line in place of its generic "Usage: aniso_remesh [OPTIONS]", and the
// options an option needs or excludes sorted by name: CLI11 2.1 lists them in the order of their
// addresses, so its help text would change from run to run
class Help_formatter : public CLI::Formatter {
public:
  std::string make_usage(const CLI::App*, std::string) const override
  {
    return "usage: aniso_remesh (--input FILE | --domain square | --image FILE) --vertices N [options]\n";
  }
  std::string make_option_opts(const CLI::Option* opt) const override
  {
    std::string s = CLI::Formatter::make_option_opts(opt);
    const std::size_t cut = std::min(s.find(" " + get_label("Needs") + ":"), s.find(" " + get_label("Excludes") + ":"));
    if(cut == std::string::npos) return s;
    s.erase(cut);
    auto names = [](const std::set<CLI::Option*>& options) {
      std::vector<std::string> n;
      for(const CLI::Option* o : options) n.push_back(o->get_name());
      std::sort(n.begin(), n.end());
      std::string list;
      for(const std::string& x : n) list += " " + x;
      return list;
    };
    if(!opt->get_needs().empty()) s += " " + get_label("Needs") + ":" + names(opt->get_needs());
    if(!opt->get_excludes().empty()) s += " " + get_label("Excludes") + ":" + names(opt->get_excludes());
    return s;
  }
};

// Declares every option of the tool on `app`, storing into `o`.
inline void declare_options(CLI::App& app, Options& o)
{
  app.name("aniso_remesh");
  app.description("aniso_remesh: remeshes a triangulated surface, the unit square or an image into an anisotropic "
                  "triangle mesh of N vertices following a Riemannian metric (Zhong, Shuai, Jin and Guo, Anisotropic "
                  "surface meshing with conformal embedding, Graphical Models 2014). The manual: doc/manual.md.");
  app.formatter(std::make_shared<Help_formatter>());
  app.footer("exit status:\n"
             "  0  success\n"
             "  1  internal failure (a bug: please report it), or cancelled\n"
             "  2  bad input: the command line, a file, the metric or a vertex count is wrong (the message names it)\n"
             "  3  valid input that this version cannot remesh (a topology without a domain, more vertices than the\n"
             "     background carries, a metric too wild for the input's resolution); the message says what was reached");
  // --help and --version act as soon as they are read, before any other option is checked (CLI11's own
  // help flag would wait for the values of the others to be validated)
  app.set_help_flag();
  app.add_flag_callback("-h,--help", [] { throw CLI::CallForHelp(); }, "print this help and exit")->trigger_on_parse();
  app.set_version_flag("--version", version_line(), "print the version and exit")->trigger_on_parse();
  // a repeated option keeps its last value, as it always did
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);

  const std::string in = "input (exactly one of --input, --image, --domain square)";
  CLI::Option* input = app.add_option("--input", o.input,
                                      "triangle mesh .off/.obj/.ply: a disk-topology surface (or planar with z = 0), or a "
                                      "closed surface of any genus")
                         ->type_name("FILE")
                         ->group(in);
  CLI::Option* image = app.add_option("--image", o.image,
                                      "PNG or PPM/PGM image; the domain is the image rectangle scaled to unit width")
                         ->type_name("FILE")
                         ->group(in);
  app.add_option("--domain", o.domain,
                 "'square': the unit square as the input (the tool builds a background resolving the metric); with "
                 "--input or --image: the parametric domain, plane | sphere | flat-torus | hyperbolic | cones | automatic "
                 "(default: from the topology, cones where the sphere or the hyperbolic disk fails, holes included; cones take "
                 "every topology but a disk, holes closed by patches; a domain that does not fit the input's topology is refused)")
    ->type_name("NAME")
    ->check(CLI::IsMember({"square", "automatic", "plane", "flat-torus", "sphere", "hyperbolic", "cones"}))
    ->group(in);
  input->excludes(image);
  app.add_flag("--no-repair", o.no_repair,
               "read --input as it is: no polygon triangulated, no duplicated point welded, no vertex of no face dropped, "
               "no face reoriented (by default these repairs are made and counted in the summary and the report)")
    ->needs(input)
    ->group(in);

  const std::string me = "metric (one of --metric, --metric-file; an image defines its own)";
  CLI::Option* metric = app.add_option("--metric", o.metric,
                                       "curvature | fig6 | fig7 | isotropic (default: isotropic; images use their colours)")
                          ->type_name("NAME")
                          ->check(CLI::IsMember({"curvature", "fig6", "fig7", "isotropic"}))
                          ->group(me);
  CLI::Option* metric_file =
    app.add_option("--metric-file", o.metric_file,
                   "one tensor per input vertex: first line the count, then m11 m12 m13 m22 m23 m33 per vertex")
      ->type_name("FILE")
      ->needs(input)
      ->group(me);
  metric->excludes(metric_file);
  image->excludes(metric)->excludes(metric_file);
  add_real(app, "--stretch-max", o.stretch_max, "R", "curvature metric: bound on the stretch ratio (default 10)",
           real("at least 1", [](double x) { return x >= 1; }))
    ->group(me);
  app.add_option("--smoothing-iterations", o.smoothing_iterations, "curvature metric: smoothing rounds of the directions (default 10)")
    ->type_name("K")
    ->transform(decimal_integer())
    ->check(CLI::Range(0, 100000))
    ->group(me);
  app.add_option("--smoothing-rings", o.smoothing_rings, "curvature metric: neighbourhood rings of the smoothing (default 2)")
    ->type_name("R")
    ->transform(decimal_integer())
    ->check(CLI::Range(0, 100))
    ->group(me);
  app.add_option("--scale-smoothing-iterations", o.scale_smoothing_iterations,
                 "curvature metric: 1-ring averaging rounds of the log scales (default: the library's)")
    ->type_name("K")
    ->transform(decimal_integer())
    ->check(CLI::Range(0, 100000))
    ->group(me);
  add_real(app, "--gradation", o.gradation, "R",
           "curvature metric: bound on the growth of the size per unit of metric length along the edges, a ratio > 1, "
           "or 0 for none (default " + shortest(Aniso_conformal::Curvature_metric_options().gradation) + ")",
           real("0 or greater than 1", [](double x) { return x == 0 || x > 1; }))
    ->group(me);
  add_real(app, "--anisotropy", o.anisotropy, "S",
           "image metric: colour weight s of the paper's eq. 9 (default 0.1 colour, 0.2 grey)",
           real("positive", [](double x) { return x > 0; }))
    ->needs(image)
    ->group(me);

  const std::string re = "remeshing";
  app.add_option("--vertices", o.vertices, "number of output vertices")
    ->type_name("N")
    ->required()
    ->transform(decimal_integer())
    ->check(CLI::Range(3LL, 100000000LL))
    ->group(re);
  app.add_option("--iterations", o.iterations, "CVT iterations (default 100)")
    ->type_name("K")
    ->transform(decimal_integer())
    ->check(CLI::Range(0LL, 1000000LL))
    ->group(re);
  app.add_option("--seed", o.seed, "seed of the initial sites (default 0; same seed, same output)")
    ->type_name("S")
    ->transform(decimal_integer())
    ->check(CLI::Range(0LL, 4294967295LL))
    ->group(re);
  app.add_option("--cvt", o.cvt, "CVT optimiser: lloyd | lbfgs (default lbfgs)")
    ->type_name("NAME")
    ->check(CLI::IsMember({"lloyd", "lbfgs"}))
    ->group(re);
  app.add_option("--background-vertices", o.background_vertices,
                 "size of the background built for --domain square (default: automatic)")
    ->type_name("N")
    ->transform(decimal_integer())
    ->check(CLI::Range(1LL, 100000000LL))
    ->group(re);
  add_real(app, "--corner-angle", o.corner_angle, "DEG",
           "boundary turning angle above which a vertex is kept as a corner (default 30)",
           real("in [0, 180)", [](double x) { return x >= 0 && x < 180; }))
    ->group(re);
  CLI::Option* feature_angle =
    add_real(app, "--feature-angle", o.feature_angle, "DEG",
             "sharp features: an edge is a crease when the normals of its two triangles differ by more than DEG "
             "(default 60; 180: none); crease components shorter than one output edge are left out; the report counts "
             "them and the creases and corners the output keeps",
             real("in [0, 180]", [](double x) { return x >= 0 && x <= 180; }))
      ->group(re);
  CLI::Option* no_features =
    app.add_flag("--no-features", o.no_features, "no sharp feature: the same as --feature-angle 180")->excludes(feature_angle)->group(re);
  app.add_flag("--keep-ragged-creases", o.keep_ragged_creases,
               "keep the crease components that look like noise (their triangles bend at other edges by half the feature "
               "angle or more: a noisy scan, a staircase crease), which are left out by default, and on a rough surface "
               "(ragged components a quarter of the crease length or more) every crease")
    ->excludes(no_features)
    ->group(re);
  app.add_flag("--no-feature-sizing", o.no_feature_sizing,
               "do not refine where two crease curves run closer than an output triangle's "
               "height (by default the metric is scaled up there so that the edges are about as long as the gap is wide, "
               "the rest a little coarser)")
    ->group(re);
  app.add_option("--curvature-sizing", o.curvature_sizing,
                 "where to refine where the surface bends more tightly than an output edge can follow (a thin limb, a tip, "
                 "a rounded rim: the metric scaled up so that the edges there are about 1.25 times the radius of curvature, "
                 "the rest a little coarser): off | cones (in the cone domain, where the limbs are; the default) | always")
    ->type_name("WHERE")
    ->check(CLI::IsMember({"off", "cones", "always"}))
    ->group(re);
  app.add_option("--features", o.features_file,
                 "--input meshes: a file of features to keep whatever their angle, one per line: two vertex indices "
                 "(counted from 0 in the mesh file) for a crease edge, one for a corner; '#' starts a comment "
                 "(with --no-features, only these)")
    ->type_name("FILE")
    ->group(re);
  app.add_option("--planar-boundary", o.planar_boundary,
                 "disks: what the plane's layout keeps of the boundary: lengths (its metric lengths, the paper's u = 0) | "
                 "shape (the input's outline) | automatic (lengths, or shape where that layout is not embedded; the default)")
    ->type_name("KIND")
    ->check(CLI::IsMember({"automatic", "shape", "lengths"}))
    ->group(re);
  app.add_option("--surface-optimization", o.surface_optimization,
                 "final flips and vertex moves of the output on the input, in the metric: off | repair (only when the "
                 "dual mesh has inverted triangles, to repair them, a triangle with an angle below 30 degrees, or follows creases; "
                 "the default; always in the cone domain and on a planar input: an image, the square) | always")
    ->type_name("WHEN")
    ->check(CLI::IsMember({"off", "repair", "always"}))
    ->group(re);
  app.add_option("--threads", o.threads, "worker threads of the curvature metric, the CVT, the dual and the quality (default 0: all cores)")
    ->type_name("T")
    ->transform(decimal_integer())
    ->check(CLI::Range(0LL, 1024LL))
    ->group(re);

  const std::string out = "outputs";
  app.add_option("--output", o.output, "the mesh (.off/.obj/.ply)")->type_name("FILE")->group(out);
  app.add_option("--report", o.report, "JSON report: quality, solver figures, CVT energies and stage timings")
    ->type_name("FILE.json")
    ->group(out);
  app.add_option("--svg", o.svg, "picture of the output (a curved one shaded), triangles coloured by quality G")
    ->type_name("FILE.svg")
    ->group(out);
  app.add_option("--histogram", o.histogram, "angle histogram")->type_name("FILE.svg")->group(out);
  app.add_flag("--quiet", o.quiet, "no summary on stdout")->group(out);
}

} // namespace detail

/// the help text (CLI11's, from the declarations): options, defaults and exit status
inline std::string usage()
{
  CLI::App app;
  Options o;
  detail::declare_options(app, o);
  return app.help();
}

/// Parses argv (without the program name); throws Invalid_input with a one-line message on any error.
/// --help and --version set `help` and `version` and skip every other check.
inline Options parse_command_line(const std::vector<std::string>& args)
{
  Options o;
  CLI::App app;
  detail::declare_options(app, o);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    app.parse(reversed);
  } catch(const CLI::CallForHelp&) {
    Options h;
    h.help = true;
    return h;
  } catch(const CLI::CallForVersion&) {
    Options v;
    v.version = true;
    return v;
  } catch(const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw Aniso_conformal::Invalid_input(what + " (see --help)");
  }
  // --domain square is an input; any other --domain names the parametric domain of --input or --image
  if(!o.domain.empty() && o.domain != "square") {
    using D = Aniso_conformal::Parametric_domain;
    for(D d : {D::AUTOMATIC, D::PLANE, D::FLAT_TORUS, D::SPHERE, D::HYPERBOLIC, D::CONE})
      if(o.domain == Aniso_conformal::domain_name(d)) o.parametric_domain = d;
    if(o.input.empty() && o.image.empty())
      throw Aniso_conformal::Invalid_input("--domain " + o.domain + " names the domain of --input; give --input FILE");
    o.domain.clear();
  }
  const int inputs = !o.input.empty() + !o.domain.empty() + !o.image.empty();
  if(inputs != 1) throw Aniso_conformal::Invalid_input("give exactly one of --input, --domain square, --image");
  if(o.metric == "curvature" && o.input.empty())
    throw Aniso_conformal::Invalid_input("--metric curvature needs a surface (--input)");
  if(o.background_vertices > 0 && o.domain.empty())
    throw Aniso_conformal::Invalid_input("--background-vertices applies to --domain square only");
  if(o.metric.empty() && o.metric_file.empty() && o.image.empty()) o.metric = "isotropic";
  return o;
}

/// The feature angle of the run, in degrees: --feature-angle, or 180 (no crease) with --no-features. Both
/// the remeshing's sharp features and the curvature metric's crease test take it.
inline double feature_angle(const Options& o) { return o.no_features ? 180.0 : o.feature_angle; }

/// The options of --metric curvature: the bound and the smoothing as given, the gradation's lengths
/// those of --vertices, the crease test of the smoothing the one of the sharp features (--feature-angle,
/// 180 with --no-features: the metric does not stop its averaging at an edge that the remeshing does not
/// keep as a crease) and --threads.
inline Aniso_conformal::Curvature_metric_options curvature_metric_options(const Options& o)
{
  Aniso_conformal::Curvature_metric_options co;
  co.stretch_max = o.stretch_max;
  co.smoothing_iterations = o.smoothing_iterations;
  co.smoothing_rings = o.smoothing_rings;
  if(o.scale_smoothing_iterations >= 0) co.scale_smoothing_iterations = o.scale_smoothing_iterations;
  if(o.gradation >= 0) co.gradation = o.gradation;
  if(o.vertices > 0) co.gradation_vertices = std::size_t(o.vertices);
  co.feature_angle = feature_angle(o);
  co.number_of_threads = o.threads;
  return co;
}

} // namespace aniso_remesh

#endif // ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H
