// Checkpoints of a wear run (docs/SCENES.md, "Long runs"): everything a wear run carries from one step to the next —
// the wear depth, the cycle, the next ΔN, the record index, the records so far, the stepper's and the contact
// solver's warm starts and counts — so that a resumed run takes exactly the steps the uninterrupted one takes. CBOR
// (RFC 8949), vectors as raw little-endian doubles; written to a file with no name (O_TMPFILE, or a temporary
// file where the file system has none), fsync'ed, named and renamed over the previous one.
//
// The document, one CBOR map:
//     format "fretwear-checkpoint", format_version, fretwear (the version), scene, scene_hash (16 hex digits),
//     stepper, cells, cycles, cycles_total, dN, next_record, steps      where the driver stands (DriveState)
//     w, records                                                       the state and what was recorded
//     contact                                                          WearContact::save()
//     stepper_state                                                    one of the stepper schemas below
//     blocks (under load.blocks only)   the block the run stands in, earlier_records (how many of `records` the
//                                       blocks before it made), and the stage's counts and settings so far
//     checksum                          fnv1a64 of the CBOR of all the rest (written by write_checkpoint)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/normal_solver.hpp"
#include "engine/scene.hpp"
#include "engine/wear_driver.hpp"
#include "engine/wear_stage.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"

namespace fretwear {

inline constexpr int kCheckpointFormat = 2;  // 2: with its checksum

// <output.dir>.checkpoint: beside the output folder, which is replaced only when a run completes.
std::filesystem::path checkpoint_path(const Scene& scene);
// Why a wear run of `scene` may not keep its checkpoint at checkpoint_path(scene) (empty: it may), each naming
// output.dir: something there that is not a regular file, or a file that is not a fretwear checkpoint
// (is_checkpoint_file()), which the run would overwrite and delete; a name too long for the file system once
// ".tmp-<pid>" is added.
std::vector<std::string> checkpoint_problems(const Scene& scene);
// True when the file at `path` is a CBOR map whose `format` is "fretwear-checkpoint": a file fretwear wrote (of any
// version or scene). Reads the file only as far as that key.
bool is_checkpoint_file(const std::filesystem::path& path);
// FNV-1a (64 bit) of the resolved scene's JSON: two scenes that resolve alike share a checkpoint.
std::uint64_t scene_hash(const Scene& scene);
// fnv1a64() of the CBOR of j without its "checksum": what "checksum" holds. It tells a checkpoint damaged after it was
// written; anyone can write one, so what it holds is still checked against the scene when resumed.
std::string checkpoint_checksum(nlohmann::json j);
// The checkpoint at `path` for this scene, or nothing when there is none. Throws InputError when the file is not a
// fretwear checkpoint, has another format or fretwear version, is damaged (its checksum), or belongs to another
// scene.
std::optional<nlohmann::json> read_checkpoint(const std::filesystem::path& path, const Scene& scene);
// Writes j atomically (an unnamed file, fsync, its name, rename, fsync of the folder).
void write_checkpoint(const std::filesystem::path& path, const nlohmann::json& j);

// The checkpoint of the wear run of `scene` (hash: scene_hash(scene)) standing at `at` with state w, out of
// cycles_total; `contact` and `stepper_state` are what the contact and the stepper saved.
nlohmann::json wear_checkpoint(const Scene& scene, std::uint64_t hash, const DriveState& at, double cycles_total,
                               const std::vector<double>& w, const std::vector<WearRecord>& records,
                               nlohmann::json contact, nlohmann::json stepper_state);
// Where the checkpoint j of the run of `scene` stands, its state (into w, whose size is the grid's) and its records.
// The contact and the stepper restore their own parts (j["contact"], j["stepper_state"]). Throws InputError when j
// was written by another stepper or on another grid.
DriveState resume_wear(const nlohmann::json& j, const Scene& scene, std::vector<double>& w,
                       std::vector<WearRecord>& records);

// The stepper schemas: what each stepper carries between steps besides w (its counts, and the warm starts or the
// derivative its next step starts from).
nlohmann::json save_implicit(const wear::ImplicitWearStepper& stepper);
void restore_implicit(const nlohmann::json& j, wear::ImplicitWearStepper& stepper, std::size_t cells);
// The explicit stepper and its rate system (the last response, from which Dormand–Prince's carried derivative is
// recomputed at w, the state restored).
nlohmann::json save_explicit(const wear::ExplicitWearStepper& stepper, const wear::WearRateSystem& rate);
void restore_explicit(const nlohmann::json& j, wear::ExplicitWearStepper& stepper, wear::WearRateSystem& rate,
                      const std::vector<double>& w);
nlohmann::json save_cycle_by_cycle(const wear::WearRateSystem& rate);
void restore_cycle_by_cycle(const nlohmann::json& j, wear::WearRateSystem& rate);

// The pieces: vectors as raw doubles (exact, ±inf included), a contact solver's state, a record.
nlohmann::json blob(const std::vector<double>& v);
std::vector<double> unblob(const nlohmann::json& j);  // throws InputError on a size that is not whole doubles
// A vector the checkpoint holds one value a cell of, a blob or a JSON array: `cells` values, or none where `empty`
// (a warm start not made yet), none of them NaN (±inf is a gap off the pad). Anyone can write a checkpoint
// (checkpoint_checksum), so one that does not fit is refused: InputError, "checkpoint: damaged", naming `what`.
std::vector<double> cell_vector(const nlohmann::json& j, std::size_t cells, const std::string& what,
                                bool empty = true);
nlohmann::json contact_state_json(const ContactState& s);
// A contact solver's state: its pressure and gap each cell_vector()s of `cells`; `what` names it in a refusal.
void contact_state_from(const nlohmann::json& j, ContactState& s, std::size_t cells, const std::string& what);
nlohmann::json record_json(const WearRecord& r);
WearRecord record_from(const nlohmann::json& j);

}  // namespace fretwear
