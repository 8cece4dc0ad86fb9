// A scene (SCENES.md): the bodies, the profile, the loads, the grid, the effects and the output. parse_scene()
// validates everything at once and fills the defaults; to_json() writes the resolved scene back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/elastic_pair.hpp"
#include "common/error.hpp"
#include "contact/profile.hpp"
#include "wear/wear_law.hpp"

namespace fretwear {

// Every problem of a scene, each "path: what is wrong; what is allowed". The command line exits with status 2.
class SceneError : public InputError {
 public:
  explicit SceneError(std::vector<std::string> problems);
  // The same problems under another heading than "the scene is invalid" (e.g. "the results cannot be written").
  SceneError(const std::string& heading, std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }
  // The scene's output folder (output.dir, or output/<name>) when its problems are elsewhere: the folder's own
  // problems (output_dir_problems()) can then be said with them, all at once.
  std::optional<std::filesystem::path> output_dir;

 private:
  std::vector<std::string> problems_;
};

// effects.tangential: one steady load cycle of partial slip.
enum class TangentialRoute { automatic, analogy, incremental };
std::string to_string(TangentialRoute r);  // "auto", "analogy", "incremental"
// Throws InputError naming the accepted words (route_words()).
TangentialRoute route_from_string(std::string_view word);
std::string route_words();

// load.control: what the cycle prescribes, the tangential load Q or the datum's relative displacement δ.
enum class LoadControl { force, displacement };
std::string to_string(LoadControl c);  // "force", "displacement"
LoadControl control_from_string(std::string_view word);  // throws InputError naming control_words()
std::string control_words();

// effects.crack
// Where a crack is: at an end of the contact under P alone, or at a position x.
enum class CrackPosition { trailing_edge, leading_edge, x };
std::string to_string(CrackPosition at);                 // "trailing_edge", "leading_edge", "x"
CrackPosition crack_position_from_string(std::string_view word);  // the two edges; throws InputError

struct CrackEffect {
  CrackPosition at = CrackPosition::trailing_edge;
  double x = 0.0;                    // m, when at == CrackPosition::x
  double angle_deg = 90.0;           // to the surface, in [15, 165]; 90 normal to it, below 90 leaning toward +x
  std::vector<double> lengths;       // crack lengths from the mouth to the tip (m)
  int quadrature = 60;               // Gauss–Jacobi points
  double face_friction = 0.0;        // Coulomb coefficient between the crack faces where they touch
};

// effects.life (PHYSICS.md, "Fretting-fatigue life"; contact/fatigue_life.hpp).
struct LifeInitiation {              // Smith–Watson–Topper by Basquin–Coffin–Manson
  double sigma_f = 0.0, b = 0.0;     // σf′ (Pa), the strength exponent (< 0)
  double eps_f = 0.0, c = 0.0;       // εf′, the ductility exponent (< 0)
  double critical_distance = 0.0;    // ℓ (m): 0 the point method at the surface, > 0 the line method
};
enum class GrowthMode { mode_I, equivalent };
std::string to_string(GrowthMode mode);  // "I", "equivalent"
GrowthMode growth_mode_from_string(std::string_view word);  // throws InputError naming the words
struct LifeGrowth {                  // Paris, with its threshold and El Haddad's short-crack correction
  double C = 0.0, m = 0.0;           // da/dN = C ΔK^m (m per cycle, ΔK in Pa·m^0.5)
  double dK_th = 0.0;                // Pa·m^0.5
  std::optional<double> a_initial;   // m; absent: the critical distance
  double a_final = 0.0;              // m
  std::optional<double> K_c;         // Pa·m^0.5
  bool el_haddad = false;
  double fatigue_limit = 0.0;        // Δσ_e (Pa), with el_haddad
  GrowthMode mode = GrowthMode::mode_I;
};
struct LifeEffect {
  std::optional<LifeInitiation> initiation;
  std::optional<LifeGrowth> growth;  // at least one of the two
  double cycles_max = 1e9;
  double a_initial() const;          // the growth's first length (m)
};

// effects.stress
struct StressEffect {
  int nx = 161, ny = 81;     // map points across and into the specimen
  double depth = 0.0;        // map depth (m); 0: the contact half-width
};

struct TangentialEffect {
  TangentialRoute route = TangentialRoute::automatic;
  int increments = 40;  // per cycle, for the incremental route
};

// effects.wear.stepper (engine/wear_stage.hpp): the contact-implicit stepper, Dormand–Prince capped below the explicit
// stability limit, or every cycle worn.
enum class WearStepper { implicit, explicit_capped, cycle_by_cycle };
std::string to_string(WearStepper stepper);                 // "implicit", "explicit", "cycle_by_cycle"
WearStepper stepper_from_string(std::string_view word);     // throws InputError naming stepper_words()
std::string stepper_words();

// effects.wear: the slip zones worn cycle after cycle.
struct WearEffect {
  wear::Law law = wear::Law::archard;  // archard (k) or energy (alpha)
  double coefficient = 0.0;         // k or alpha (1/Pa), both bodies together
  double pad_fraction = 0.5;        // share of the wear on the pad
  // Given per body (k_pad and k_specimen, or alpha_pad and alpha_specimen): coefficient is their sum and
  // pad_fraction the pad's over it.
  bool per_body = false;
  double coefficient_pad = 0.0, coefficient_specimen = 0.0;  // 1/Pa
  double cycles = 0.0;              // a whole number of cycles
  WearStepper stepper = WearStepper::implicit;
  double tolerance = 1e-3;          // relative, on the worn profile, per step
  std::vector<double> record;       // cycles at which the state is recorded (increasing, last = cycles)
  int record_count = 16;            // when record was given as a count (log-spaced)
};

// One block of load.blocks: a loading held for a number of cycles, given as load.Q (amplitude or ratio), load.delta
// (displacement control) or load.history; exactly one of the three. Bulk stress: load.bulk_stress for Q and delta.
struct LoadBlock {
  std::optional<double> Q_amplitude, Q_ratio;  // as Scene's
  std::optional<double> delta;                 // > 0: displacement control
  std::vector<std::array<double, 4>> history;  // as Scene's
  double cycles = 0.0;                         // whole, ≥ 1
};

struct Scene {
  std::string name;                      // letters, digits, '_', '-', '.'; names the output folder
  PlaneState plane = PlaneState::strain;
  bool similar = true;                   // materials given as "both"
  Material pad, specimen;
  ProfileSpec profile;
  double P = 0.0;                        // normal load per unit length (N/m)
  std::optional<double> friction;        // Coulomb coefficient f (needed by tangential effects)
  std::optional<double> Q_amplitude;     // load.Q.amplitude (N/m)
  std::optional<double> Q_ratio;         // load.Q.ratio = Q/(fP)
  double bulk_stress = 0.0;              // load.bulk_stress.amplitude: σ in the specimen in phase with Q (Pa)
  LoadControl control = LoadControl::force;  // load.control
  std::optional<double> delta;           // load.delta: the amplitude of δ under displacement control (m)
  std::vector<std::array<double, 4>> history;  // load.history: [t (s), P (N/m), Q (N/m), σ_bulk (Pa)], the last
                                               // point repeating the first's P, Q, σ; empty: the cycle of load.Q
  // load.blocks: the loadings the wear stage runs once, in order, each for its cycles (their sum is wear.cycles).
  // The scene's own load (Q_amplitude, Q_ratio, control, delta, history) is the first block's: the cycle stage's.
  std::vector<LoadBlock> blocks;
  std::optional<TangentialEffect> tangential;
  bool tangential_implied = false;       // added because wear needs the cycle
  std::optional<WearEffect> wear;
  std::optional<StressEffect> stress;
  std::optional<CrackEffect> crack;
  std::optional<LifeEffect> life;

  // Q at the top of the cycle (N/m), from the amplitude or the ratio (the largest |Q| of a history); 0 without a
  // tangential load.
  double Q_max() const;
  // The largest normal load of the scene (N/m): P, or a history's largest.
  double P_max() const;
  int cells = 1024;                      // grid.cells
  std::optional<std::pair<double, double>> window;  // grid.window (m); chosen from the contact when absent
  std::optional<double> reference_depth;  // grid.reference_depth (m): the displacement datum's depth below the
                                          // contact centre; 10 contact half-widths when absent
  std::filesystem::path output_dir;      // output.dir; default output/<name>
  bool plots = true;                     // output.plots

  // The scene with every default filled in (window as resolved when given).
  nlohmann::json to_json() const;
};

// Why wear cannot be computed under force control once Q reaches f P (N/m both): the bodies slide, and the slip,
// hence the wear, is not determined. One sentence for the scene's check and the wear contacts' alike.
std::string sliding_under_force_control(double Q, double fP);

// The largest scene file read, the deepest nesting of its objects and arrays (a scene needs about 20: profiles
// nest 8 levels, two each), and the grid sizes accepted.
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;
constexpr std::size_t kMaxSceneDepth = 64;
constexpr int kMinCells = 16;
constexpr int kMaxCells = 1 << 20;

// The spans a scene's dimensional numbers must lie in (SCENES.md, "Ranges"; docs/scene.schema.json states the same
// bounds). They refuse magnitudes no contact has, which the solvers would otherwise carry into overflow, denormals
// or numbers without a digit left (a window of ±1e200 m crashed, a radius of 1e-308 m gave a slip of 1e205 m), and
// leave room for every contact that plane linear elasticity describes.
namespace spans {
// Lengths (radii, half-widths, amplitudes, wavelengths, depths, crack lengths), m: from 1 nm, a few atomic spacings,
// below which a continuum is no model of the bodies, to 100 m, beyond any body whose contact is still plane (a
// wheel on a rail: 0.5 m). Not 1 km: Profile looks for the lowest point within some 400 m of a profile's centre, and
// a flat or a table wider than that would be refused there, with a message about tilt.
constexpr double kMinLength = 1e-9;
constexpr double kMaxLength = 100.0;
// Positions (profile offsets, table points and heights, window ends, a crack's x), m: no farther from the origin
// than the largest length. A window's ends are at least kMinLength apart.
constexpr double kMaxPosition = kMaxLength;
// The displacement amplitude δ, m: from kMinLength up to (not including) 1 m, the cycle of a fretting contact, not
// a sliding one.
constexpr double kMaxDelta = 1.0;
// Young's moduli, Pa: from 1 kPa (the softest gels) to 1e13 Pa, ten times diamond's (about 1.1e12 Pa). No denormals.
constexpr double kMinModulus = 1e3;
constexpr double kMaxModulus = 1e13;
// Stresses (load.bulk_stress, a history's sigma_bulk), Pa: |σ| up to 1e12 Pa, about diamond's modulus. Linear
// elasticity needs strains well below one, so a stress of the order of E is already beyond its reach.
constexpr double kMaxStress = 1e12;
// Loads per unit length of contact (P, Q, a history's P and Q), N/m: P from 1 µN on a metre of contact; up to 1e12
// N/m, kMaxStress over a contact 1 m wide.
constexpr double kMinLoad = 1e-6;
constexpr double kMaxLoad = 1e12;
// load.Q.ratio = Q/(fP): from 1 on the bodies slide and Q saturates at fP; 100 leaves room for any study of it.
constexpr double kMaxLoadRatio = 100.0;
// The times of a load history, s: |t| up to 1e9 s (some 30 years for a cycle).
constexpr double kMaxTime = 1e9;
// Wear coefficients (Archard k, energy alpha), 1/Pa: from 1e-30, far below any measured one (about 1e-20 to
// 1e-12), up to (not including) 1.
constexpr double kMinWearCoefficient = 1e-30;
constexpr double kMaxWearCoefficient = 1.0;
}  // namespace spans

// Validates j as a scene; throws SceneError listing every problem. default_name names a scene without "name";
// scene_dir is the folder a table's relative "file" is read from (empty: the working folder).
Scene parse_scene(const nlohmann::json& j, const std::string& default_name = "scene",
                  const std::filesystem::path& scene_dir = {});
// Reads the JSON text of a scene and validates it (parse_scene). Problems of the text are SceneErrors naming the
// JSON path and the line, listed before parse_scene's: a key given twice in an object, a number that overflows a
// double, nesting deeper than kMaxSceneDepth; and text that is not JSON (UTF-8), named by source. Only a key given
// twice lets parse_scene run as well; the others stop the reading. Throws nothing but SceneError (and bad_alloc).
Scene parse_scene_text(std::string_view text, const std::string& default_name = "scene",
                       const std::string& source = "the scene", const std::filesystem::path& scene_dir = {});
// "-" for a scene path: the scene is read from standard input.
inline constexpr const char* kStdinScene = "-";
// Reads a scene file and parses its text, a table's relative file read from the scene file's folder; file problems
// (missing, a directory, not a regular file, too large) are SceneErrors too. The path kStdinScene reads standard
// input to its end instead: the scene is named "stdin" unless it names itself, and a table's relative file is read
// from the working folder.
Scene load_scene(const std::filesystem::path& path);
// The default scene, as `fretwear defaults [--effect NAME]` prints it: PHYSICS.md's Hertz contact with every effect
// and every key written out (required ones at that case's values), or with one effect (and the load cycle it
// needs); "normal" gives the normal contact alone. Throws InputError for an effect it does not know.
nlohmann::json default_scene_json(const std::string& effect = "");
std::vector<std::string> default_effect_words();

// FNV-1a, 64 bits (Fowler, Noll and Vo), written "fnv1a64:" and 16 hex digits: the checksum of a measured profile's
// file, and of each file a results folder's marker lists.
std::string fnv1a64(std::string_view bytes);

// Whether `text` is UTF-8, which the JSON fretwear writes (summary.json, scene.resolved.json) must be.
bool utf8_text(const std::string& text);
// A path holding a NUL byte: every call of the file system would end it there, and reach another file or folder.
// A problem says of it kHoldsNul.
bool holds_nul(std::string_view path);
inline constexpr const char* kHoldsNul =
    "holds a NUL byte, where the file system would end the path; give the path without it";

}  // namespace fretwear
