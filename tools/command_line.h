// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Command-line parsing of aniso_remesh, kept apart from main() so that it is tested (and fuzzed) alone.

#ifndef ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H
#define ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H

#include <Aniso_conformal/Exceptions.h>
#include <Aniso_conformal/parameters.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace aniso_remesh {

struct Options {
  // input: exactly one of these
  std::string input, domain, image;
  // --domain with --input or --image: the parametric domain, checked against the topology
  Aniso_conformal::Parametric_domain parametric_domain = Aniso_conformal::Parametric_domain::AUTOMATIC;
  // metric
  std::string metric;       // curvature | fig6 | fig7 | isotropic (empty: from --metric-file or image)
  std::string metric_file;
  double stretch_max = 10;
  int smoothing_iterations = 10;
  int smoothing_rings = 2;
  double anisotropy = -1;   // image only; default 0.1 colour, 0.2 grey
  // remeshing
  long long vertices = -1;
  long long iterations = 100;
  unsigned seed = 0;
  std::string cvt = "lbfgs";
  long long background_vertices = 0;
  double corner_angle = 30;
  unsigned threads = 0;
  // outputs
  std::string output, report, svg, histogram;
  bool quiet = false, help = false, version = false;
};

inline const char* usage()
{
  return "usage: aniso_remesh (--input FILE | --domain square | --image FILE) --vertices N [options]\n"
         "\n"
         "input (one of):\n"
         "  --input FILE              triangle mesh .off/.obj/.ply: a disk-topology surface (or planar with z = 0),\n"
         "                            or a closed surface of any genus\n"
         "  --domain square           the unit square; the tool builds a background resolving the metric\n"
         "  --image FILE              PNG or PPM/PGM image; the domain is the image rectangle scaled to unit width\n"
         "metric (one of):\n"
         "  --metric-file FILE        one tensor per input vertex: first line the count, then m11 m12 m13 m22 m23 m33\n"
         "  --metric NAME             curvature | fig6 | fig7 | isotropic (default: isotropic; images use their colours)\n"
         "  --stretch-max R           curvature metric: bound on the stretch ratio (default 10)\n"
         "  --smoothing-iterations K  curvature metric: smoothing rounds (default 10)\n"
         "  --smoothing-rings R       curvature metric: neighbourhood rings of the smoothing (default 2)\n"
         "  --anisotropy S            image metric: colour weight s of the paper's eq. 9 (default 0.1 colour, 0.2 grey)\n"
         "remeshing:\n"
         "  --domain NAME             with --input: plane | sphere | flat-torus | hyperbolic (default: from the topology; a domain\n"
         "                            that does not fit the input's topology is refused)\n"
         "  --vertices N              number of output vertices (required)\n"
         "  --iterations K            CVT iterations (default 100)\n"
         "  --seed S                  seed of the initial sites (default 0; same seed, same output)\n"
         "  --cvt lloyd|lbfgs         CVT optimiser (default lbfgs)\n"
         "  --background-vertices N   size of the background built for --domain square (default: automatic)\n"
         "  --corner-angle DEG        boundary turning angle above which a vertex is kept as a corner (default 30)\n"
         "  --threads T               worker threads of the CVT (default: all cores)\n"
         "outputs:\n"
         "  --output FILE             the mesh (.off/.obj/.ply)\n"
         "  --report FILE.json        quality, solver figures, CVT energies and stage timings\n"
         "  --svg FILE.svg            picture of the output (a curved one shaded), triangles coloured by quality G\n"
         "  --histogram FILE.svg      angle histogram\n"
         "  --quiet                   no summary on stdout\n"
         "  --help, --version\n"
         "\n"
         "exit status: 0 success, 2 bad input (the message names the problem), 1 internal failure\n";
}

namespace detail {
inline double to_double(const std::string& opt, const std::string& v)
{
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if(v.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
    throw Aniso_conformal::Invalid_input("option " + opt + ": '" + v + "' is not a finite number");
  return x;
}
inline long long to_integer(const std::string& opt, const std::string& v, long long lo, long long hi)
{
  errno = 0;
  char* end = nullptr;
  const long long x = std::strtoll(v.c_str(), &end, 10);
  if(v.empty() || *end != '\0' || errno == ERANGE)
    throw Aniso_conformal::Invalid_input("option " + opt + ": '" + v + "' is not an integer");
  if(x < lo || x > hi)
    throw Aniso_conformal::Invalid_input("option " + opt + ": " + v + " is out of range [" + std::to_string(lo) + ", " +
                                         std::to_string(hi) + "]");
  return x;
}
} // namespace detail

// Parses argv (without the program name); throws Invalid_input with a one-line message on any error.
inline Options parse_command_line(const std::vector<std::string>& args)
{
  Options o;
  bool metric_given = false;
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if(i + 1 >= args.size()) throw Aniso_conformal::Invalid_input("option " + a + " needs a value");
      return args[++i];
    };
    if(a == "--help" || a == "-h") o.help = true;
    else if(a == "--version") o.version = true;
    else if(a == "--quiet") o.quiet = true;
    else if(a == "--input") o.input = value();
    else if(a == "--domain") o.domain = value();
    else if(a == "--image") o.image = value();
    else if(a == "--metric") { o.metric = value(); metric_given = true; }
    else if(a == "--metric-file") o.metric_file = value();
    else if(a == "--stretch-max") o.stretch_max = detail::to_double(a, value());
    else if(a == "--smoothing-iterations") o.smoothing_iterations = int(detail::to_integer(a, value(), 0, 100000));
    else if(a == "--smoothing-rings") o.smoothing_rings = int(detail::to_integer(a, value(), 0, 100));
    else if(a == "--anisotropy") o.anisotropy = detail::to_double(a, value());
    else if(a == "--vertices") o.vertices = detail::to_integer(a, value(), 0, 100000000);
    else if(a == "--iterations") o.iterations = detail::to_integer(a, value(), 0, 1000000);
    else if(a == "--seed") o.seed = unsigned(detail::to_integer(a, value(), 0, 4294967295LL));
    else if(a == "--cvt") o.cvt = value();
    else if(a == "--background-vertices") o.background_vertices = detail::to_integer(a, value(), 1, 100000000);
    else if(a == "--corner-angle") o.corner_angle = detail::to_double(a, value());
    else if(a == "--threads") o.threads = unsigned(detail::to_integer(a, value(), 0, 1024));
    else if(a == "--output") o.output = value();
    else if(a == "--report") o.report = value();
    else if(a == "--svg") o.svg = value();
    else if(a == "--histogram") o.histogram = value();
    else throw Aniso_conformal::Invalid_input("unknown option '" + a + "' (see --help)");
  }
  if(o.help || o.version) return o;
  // --domain square is an input; any other --domain names the parametric domain of --input or --image
  if(!o.domain.empty() && o.domain != "square") {
    using D = Aniso_conformal::Parametric_domain;
    const D all[] = {D::AUTOMATIC, D::PLANE, D::FLAT_TORUS, D::SPHERE, D::HYPERBOLIC};
    bool known = false;
    for(D d : all)
      if(o.domain == Aniso_conformal::domain_name(d)) { o.parametric_domain = d; known = true; }
    if(!known)
      throw Aniso_conformal::Invalid_input("unknown domain '" + o.domain +
                                           "' (square; or, with --input: plane, flat-torus, sphere, hyperbolic, automatic)");
    if(o.input.empty() && o.image.empty())
      throw Aniso_conformal::Invalid_input("--domain " + o.domain + " names the domain of --input; give --input FILE");
    o.domain.clear();
  }
  const int inputs = !o.input.empty() + !o.domain.empty() + !o.image.empty();
  if(inputs != 1) throw Aniso_conformal::Invalid_input("give exactly one of --input, --domain square, --image");
  if(o.vertices < 0) throw Aniso_conformal::Invalid_input("--vertices N is required");
  if(o.vertices < 3) throw Aniso_conformal::Invalid_input("--vertices must be at least 3");
  if(metric_given && !o.metric_file.empty()) throw Aniso_conformal::Invalid_input("give either --metric or --metric-file");
  if(metric_given && o.metric != "curvature" && o.metric != "fig6" && o.metric != "fig7" && o.metric != "isotropic")
    throw Aniso_conformal::Invalid_input("unknown metric '" + o.metric + "' (curvature, fig6, fig7, isotropic)");
  if(!o.metric_file.empty() && o.input.empty())
    throw Aniso_conformal::Invalid_input("--metric-file needs --input (one tensor per input vertex)");
  if(!o.image.empty() && (metric_given || !o.metric_file.empty()))
    throw Aniso_conformal::Invalid_input("an image defines its own metric: use --anisotropy, not --metric");
  if(o.anisotropy != -1 && o.image.empty()) throw Aniso_conformal::Invalid_input("--anisotropy applies to --image only");
  if(o.anisotropy != -1 && !(o.anisotropy > 0)) throw Aniso_conformal::Invalid_input("--anisotropy must be positive");
  if(o.metric == "curvature" && o.input.empty())
    throw Aniso_conformal::Invalid_input("--metric curvature needs a surface (--input)");
  if(!(o.stretch_max >= 1)) throw Aniso_conformal::Invalid_input("--stretch-max must be at least 1");
  if(o.cvt != "lloyd" && o.cvt != "lbfgs") throw Aniso_conformal::Invalid_input("--cvt must be lloyd or lbfgs");
  if(!(o.corner_angle >= 0 && o.corner_angle < 180)) throw Aniso_conformal::Invalid_input("--corner-angle must be in [0, 180)");
  if(o.background_vertices > 0 && o.domain.empty())
    throw Aniso_conformal::Invalid_input("--background-vertices applies to --domain square only");
  if(metric_given && o.metric.empty()) o.metric = "isotropic";
  if(!metric_given && o.metric_file.empty() && o.image.empty()) o.metric = "isotropic";
  return o;
}

} // namespace aniso_remesh

#endif // ANISO_CONFORMAL_TOOLS_COMMAND_LINE_H
