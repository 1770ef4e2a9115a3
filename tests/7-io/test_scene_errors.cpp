// Error reporting of `mbsopt simulate` on bad scene files (problems/scenes/README.md): every file of
// tests/scenes/bad/ has exactly one defect and a first line
//
//   # expect: <LINE> <fragment>
//
// LINE is the 1-based line the error must name; `a|b` accepts either line and `-` a message without
// a line (`FILE: error: ...`). The fragment is matched case-insensitively; `x|y` accepts either.
// For each file the command must exit non-zero, print exactly one line on stderr of the form
// `FILE:LINE:COLUMN: error: <what>` (FILE exactly as given on the command line) and leave nothing in
// the directory of its --out file. Each file is its own test case, so new files are picked up by
// adding them to the directory. The command is run with posix_spawn (no shell, explicit working
// directory, a time limit), with stdin from /dev/null and stdout/stderr in files.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/fuzz/input_arguments.hpp"

extern char** environ;

namespace mbsopt {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = MBSOPT_SOURCE_DIR;
const fs::path kBadScenes = kSourceDir / "tests" / "scenes" / "bad";
constexpr auto kTimeLimit = std::chrono::seconds(60);  // generous for the sanitizer build

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// The lines of a file without their terminators.
std::vector<std::string> fileLines(const fs::path& path) {
  std::vector<std::string> lines;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

/// What the message for one bad input must look like.
struct Expectation {
  std::vector<int> lines;                // accepted lines (1-based)
  bool any_line = false;                 // any line of the file is accepted
  bool line_optional = false;            // `FILE: error: ...` accepted too
  std::vector<std::string> fragments;    // lower case; one of them must occur
};

/// Parses the first line `# expect: <LINE> <fragment>`; nullopt when it is missing or malformed.
std::optional<Expectation> parseExpectation(const fs::path& file) {
  const std::vector<std::string> lines = fileLines(file);
  if (lines.empty()) return std::nullopt;
  static const std::regex pattern(R"(^#\s*expect:\s*(\S+)\s+(.*\S)\s*$)");
  std::smatch match;
  if (!std::regex_match(lines.front(), match, pattern)) return std::nullopt;
  Expectation expectation;
  for (const std::string& alternative : split(match[1].str(), '|')) {
    if (alternative == "-") {
      expectation.line_optional = true;
    } else if (!alternative.empty() &&
               std::all_of(alternative.begin(), alternative.end(), [](unsigned char c) { return std::isdigit(c); })) {
      expectation.lines.push_back(std::stoi(alternative));
    } else {
      return std::nullopt;
    }
  }
  for (const std::string& fragment : split(match[2].str(), '|'))
    if (!fragment.empty()) expectation.fragments.push_back(lower(fragment));
  if (expectation.fragments.empty()) return std::nullopt;
  return expectation;
}

/// A fresh empty directory, removed with its content at the end of the scope.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "mbsopt_scene_errors_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + std::string(std::strerror(errno)));
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

struct RunResult {
  bool started = false;
  bool timed_out = false;
  bool exited = false;  // normal exit (not killed by a signal)
  int exit_code = -1;
  int signal = 0;
  std::string stderr_text;
};

/// Runs `mbsopt args...` in `working_directory`, stdout to `stdout_file`, stderr to `stderr_file`.
RunResult runMbsopt(const std::vector<std::string>& args, const fs::path& working_directory,
                    const fs::path& stdout_file, const fs::path& stderr_file) {
  RunResult result;
  std::vector<std::string> argv_strings{MBSOPT_EXECUTABLE};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : argv_strings) argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, working_directory.c_str());
  pid_t pid = 0;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) return result;
  result.started = true;

  const auto deadline = std::chrono::steady_clock::now() + kTimeLimit;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return result;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFEXITED(status)) {
    result.exited = true;
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  result.stderr_text = readText(stderr_file);
  return result;
}

std::string listDirectory(const fs::path& directory) {
  std::string names;
  for (const auto& entry : fs::directory_iterator(directory)) {
    names += ' ';
    names += entry.path().filename().string();
  }
  return names.empty() ? " (empty)" : names;
}

/// Runs `simulate <scene_argument> <extra...> --out <tmp>/run/out.csv` from `working_directory` and
/// checks the contract against `expectation`; `scene_lines` (the file's text) bounds the column.
/// With `existing_out`, out.csv is first written with that text and must be left as it was.
void expectOneLineError(const std::string& scene_argument, const std::vector<std::string>& extra,
                        const Expectation& expectation, const fs::path& working_directory,
                        const std::vector<std::string>& scene_lines,
                        const std::optional<std::string>& existing_out = std::nullopt) {
  TemporaryDirectory temporary;
  const fs::path run_dir = temporary.path() / "run";
  fs::create_directory(run_dir);
  const fs::path stderr_file = run_dir / "stderr.txt";
  const fs::path out_file = run_dir / "out.csv";
  if (existing_out) std::ofstream(out_file, std::ios::binary) << *existing_out;

  std::vector<std::string> args{"simulate", scene_argument};
  args.insert(args.end(), extra.begin(), extra.end());
  args.insert(args.end(), {"--out", out_file.string()});
  const RunResult run = runMbsopt(args, working_directory, temporary.path() / "stdout.txt", stderr_file);
  ASSERT_TRUE(run.started) << "could not start " << MBSOPT_EXECUTABLE;
  ASSERT_FALSE(run.timed_out) << "mbsopt did not finish within " << kTimeLimit.count() << " s";

  const std::string& text = run.stderr_text;
  SCOPED_TRACE("stderr was:\n" + text);
  EXPECT_TRUE(run.exited) << "mbsopt was killed by signal " << run.signal;
  EXPECT_NE(run.exit_code, 0) << "mbsopt exited with status 0 on a bad scene";

  // Nothing but the stderr capture (and an out.csv that was there before, unchanged) is left next to
  // the --out file.
  std::vector<fs::path> left;
  for (const auto& entry : fs::directory_iterator(run_dir))
    if (entry.path() != stderr_file && !(existing_out && entry.path() == out_file))
      left.push_back(entry.path().filename());
  EXPECT_TRUE(left.empty()) << "files left in the output directory:" << listDirectory(run_dir);
  if (existing_out) {
    EXPECT_TRUE(fs::exists(out_file)) << "the existing --out file was removed";
    EXPECT_EQ(readText(out_file), *existing_out) << "the existing --out file was changed";
  }

  // Exactly one non-empty line.
  std::vector<std::string> lines = split(text, '\n');
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  ASSERT_EQ(lines.size(), 1u) << "stderr must hold exactly one line";
  const std::string& line = lines.front();
  ASSERT_FALSE(line.empty()) << "stderr line is empty";
  EXPECT_NE(line.find("error:"), std::string::npos) << "no 'error:' in: " << line;

  // FILE:LINE:COLUMN: error: what   or   FILE: error: what
  const std::string prefix = scene_argument + ":";
  ASSERT_EQ(line.rfind(prefix, 0), 0u) << "the line must start with '" << prefix << "': " << line;
  const std::string rest = line.substr(prefix.size());
  // The text after "error: " must not be empty.
  static const std::regex located(R"(^(\d+):(\d+): error: (\S.*)$)");
  static const std::regex unlocated(R"(^ error: (\S.*)$)");
  std::smatch match;
  std::string reason;  // the text after "error: ", where the fragment is looked for (not in the path)
  if (std::regex_match(rest, match, located)) {
    const int line_number = std::stoi(match[1].str());
    const int column = std::stoi(match[2].str());
    reason = match[3].str();
    std::string accepted;
    for (int l : expectation.lines) {
      accepted += ' ';
      accepted += std::to_string(l);
    }
    if (expectation.line_optional) accepted += " (or no line)";
    const bool expected_line =
        expectation.any_line ||
        std::find(expectation.lines.begin(), expectation.lines.end(), line_number) != expectation.lines.end();
    EXPECT_TRUE(expected_line) << "names line " << line_number << ", expected line" << accepted << ": " << line;
    if (!scene_lines.empty()) {
      EXPECT_LE(line_number, static_cast<int>(scene_lines.size()))
          << "names a line past the end of the " << scene_lines.size() << "-line file: " << line;
    }
    EXPECT_GE(column, 1) << "columns are 1-based: " << line;
    if (line_number >= 1 && line_number <= static_cast<int>(scene_lines.size())) {
      EXPECT_LE(column, static_cast<int>(scene_lines[static_cast<std::size_t>(line_number - 1)].size()) + 1)
          << "column beyond the end of line " << line_number << ": " << line;
    }
  } else if (std::regex_match(rest, match, unlocated)) {
    reason = match[1].str();
    EXPECT_TRUE(expectation.line_optional) << "the message names no line, expected line "
                                           << (expectation.lines.empty() ? 0 : expectation.lines.front()) << ": "
                                           << line;
  } else {
    ADD_FAILURE() << "not of the form FILE:LINE:COLUMN: error: <what> (or FILE: error: <what>): " << line;
  }

  const std::string lowered = lower(reason);
  std::string wanted;
  bool found = false;
  for (const std::string& fragment : expectation.fragments) {
    wanted += (wanted.empty() ? "'" : " or '") + fragment + "'";
    found = found || lowered.find(fragment) != std::string::npos;
  }
  EXPECT_TRUE(found) << "the message should contain " << wanted << ": " << line;
}

// ---- the files of tests/scenes/bad/ ----

std::vector<fs::path> badSceneFiles() {
  std::vector<fs::path> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(kBadScenes, error))
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string testName(const testing::TestParamInfo<fs::path>& info) {
  std::string name = info.param.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class BadScene : public testing::TestWithParam<fs::path> {};

TEST_P(BadScene, OneLineErrorAtTheDefect) {
  const fs::path& file = GetParam();
  const std::optional<Expectation> expectation = parseExpectation(file);
  ASSERT_TRUE(expectation.has_value()) << file << ": the first line must be '# expect: <LINE> <fragment>'";
  expectOneLineError(file.string(), {}, *expectation, kSourceDir, fileLines(file));
}

INSTANTIATE_TEST_SUITE_P(Files, BadScene, testing::ValuesIn(badSceneFiles()), testName);

TEST(BadSceneSuite, HasAtLeast25Files) { EXPECT_GE(badSceneFiles().size(), 25u) << "in " << kBadScenes; }

TEST(BadSceneSuite, EveryFileStatesItsExpectation) {
  for (const fs::path& file : badSceneFiles())
    EXPECT_TRUE(parseExpectation(file).has_value()) << file << ": first line must be '# expect: <LINE> <fragment>'";
}

// A bad file named by a path relative to the working directory is reported under that path.
TEST(BadSceneSuite, RelativePathIsReportedAsGiven) {
  const fs::path file = kBadScenes / "negative_mass.yaml";
  const std::optional<Expectation> expectation = parseExpectation(file);
  ASSERT_TRUE(expectation.has_value());
  expectOneLineError("tests/scenes/bad/negative_mass.yaml", {}, *expectation, kSourceDir, fileLines(file));
}

// A bad scene leaves an --out file that existed before untouched (it writes nothing at all).
TEST(BadSceneSuite, ExistingOutputIsLeftUntouched) {
  const fs::path file = kBadScenes / "zero_mass.yaml";
  const std::optional<Expectation> expectation = parseExpectation(file);
  ASSERT_TRUE(expectation.has_value());
  expectOneLineError(file.string(), {}, *expectation, kSourceDir, fileLines(file), "t,previous\n0,1\n");
}

// ---- the fuzzing regressions: every input that ever hung or crashed the program ----
// tests/fuzz/regressions/ (docs/fuzzing.md) keeps them byte for byte, without an expectation line:
// each must finish well within the time limit, either as a run (exit 0; under the sanitizers, with
// no report) or with one error line naming the file (any line, any message) and a non-zero exit.
// Their "#!" lines are command-line arguments, passed on as the fuzz target does.

const fs::path kFuzzRegressions = kSourceDir / "tests" / "fuzz" / "regressions";

std::vector<fs::path> fuzzRegressionFiles() {
  std::vector<fs::path> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(kFuzzRegressions, error))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegression : public testing::TestWithParam<fs::path> {};

TEST_P(FuzzRegression, OneLineErrorNoHang) {
  const fs::path& file = GetParam();
  Expectation any;
  any.any_line = true;
  any.line_optional = true;
  any.fragments = {""};
  std::vector<std::string> extra = fuzz::inputArguments(readText(file));
  extra.insert(extra.end(), {"--t-end", "0.05"});
  TemporaryDirectory temporary;
  std::vector<std::string> args{"simulate", file.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult run = runMbsopt(args, kSourceDir, temporary.path() / "stdout.txt", temporary.path() / "stderr.txt");
  ASSERT_TRUE(run.started) << "could not start " << MBSOPT_EXECUTABLE;
  ASSERT_FALSE(run.timed_out) << "mbsopt did not finish within " << kTimeLimit.count() << " s";
  ASSERT_TRUE(run.exited) << "mbsopt was killed by signal " << run.signal << "; stderr:\n" << run.stderr_text;
  if (run.exit_code == 0) return;  // a valid scene that once crashed: it runs
  expectOneLineError(file.string(), extra, any, kSourceDir, fileLines(file));
}

INSTANTIATE_TEST_SUITE_P(Files, FuzzRegression, testing::ValuesIn(fuzzRegressionFiles()), testName);

TEST(FuzzRegressionSuite, HoldsTheYamlCppHangs) { EXPECT_GE(fuzzRegressionFiles().size(), 4u) << "in " << kFuzzRegressions; }

// ---- inputs that are not a bad file: a missing file, bad --set overrides ----

// A valid scene: the bad --set values below are its only defect. Line numbers matter.
constexpr const char* kPendulum =
    "# a valid pendulum for the --set tests\n"                                                          // 1
    "gravity: [0, 0, -9.81]\n"                                                                          // 2
    "settings:\n"                                                                                       // 3
    "  step: 1.0e-3\n"                                                                                  // 4
    "  end_time: 0.01\n"                                                                                // 5
    "elements:\n"                                                                                       // 6
    "  - {name: arm, type: revolute, parent: ground, axis: [0, 1, 0], q0: 90 deg}\n"                     // 7
    "bodies:\n"                                                                                         // 8
    "  - name: bob\n"                                                                                   // 9
    "    frame: arm\n"                                                                                  // 10
    "    mass: 1.0\n"                                                                                   // 11
    "    com: [0, 0, -1]\n"                                                                             // 12
    "    Ixx: 0.01\n"                                                                                   // 13
    "    Iyy: 0.01\n"                                                                                   // 14
    "    Izz: 0.01\n";                                                                                  // 15
constexpr int kMassLine = 11, kStepLine = 4, kAxisLine = 7;

class SceneOverride : public testing::Test {
 protected:
  void SetUp() override {
    scene_ = scene_dir_.path() / "pendulum.yaml";
    std::ofstream(scene_) << kPendulum;
    lines_ = fileLines(scene_);
  }
  Expectation expect(std::vector<int> lines, std::vector<std::string> fragments) const {
    Expectation e;
    e.lines = std::move(lines);
    e.line_optional = e.lines.empty();
    for (std::string& f : fragments) e.fragments.push_back(lower(f));
    return e;
  }
  void expectError(const std::vector<std::string>& extra, const Expectation& expectation) const {
    expectOneLineError(scene_.string(), extra, expectation, scene_dir_.path(), lines_);
  }

  TemporaryDirectory scene_dir_;
  fs::path scene_;
  std::vector<std::string> lines_;
};

// The control: without a bad override the scene runs and writes its CSV, so the failures below are
// caused by the override alone.
TEST_F(SceneOverride, ValidSceneAndOverrideRun) {
  TemporaryDirectory temporary;
  const fs::path out = temporary.path() / "out.csv";
  const RunResult run = runMbsopt({"simulate", scene_.string(), "--set", "bob.mass=2", "--out", out.string()},
                                  scene_dir_.path(), temporary.path() / "stdout.txt", temporary.path() / "stderr.txt");
  ASSERT_TRUE(run.started);
  ASSERT_FALSE(run.timed_out);
  EXPECT_TRUE(run.exited && run.exit_code == 0) << "stderr:\n" << run.stderr_text;
  EXPECT_TRUE(fs::exists(out));
}

TEST_F(SceneOverride, UnknownParameterName) { expectError({"--set", "bob.masss=2"}, expect({}, {"bob.masss"})); }

TEST_F(SceneOverride, ValueNotANumber) {
  // No line in the file is wrong: FILE: error: ..., naming the bad value.
  expectError({"--set", "bob.mass=abc"}, expect({}, {"abc"}));
}

TEST_F(SceneOverride, ValueOverflowsToInfinity) {
  Expectation e = expect({kMassLine}, {"1e999", "finite", "inf", "range", "overflow"});
  e.line_optional = true;  // the value is the override's, not the file's: either form is fine
  expectError({"--set", "bob.mass=1e999"}, e);
}

TEST_F(SceneOverride, NegativeMassPointsAtTheMass) {
  expectError({"--set", "bob.mass=-1"}, expect({kMassLine}, {"mass"}));
}

TEST_F(SceneOverride, ZeroStepPointsAtTheStep) {
  expectError({"--set", "settings.step=0"}, expect({kStepLine}, {"step"}));
}

TEST_F(SceneOverride, MissingEqualsSign) {
  expectError({"--set", "bob.mass"}, expect({}, {"name=value", "="}));
}

TEST_F(SceneOverride, ZeroAxisPointsAtTheAxis) {
  expectError({"--set", "arm.axis.y=0"}, expect({kAxisLine}, {"axis"}));
}

TEST(SceneFileMissing, NamesTheFileWithoutALine) {
  TemporaryDirectory temporary;
  const fs::path missing = temporary.path() / "no_such_scene.yaml";
  Expectation expectation;
  expectation.line_optional = true;
  expectation.fragments = {"cannot", "no such", "not exist", "not found", "unable", "failed"};
  expectOneLineError(missing.string(), {}, expectation, temporary.path(), {});
}

// A directory is not a readable scene file: FILE: error: ..., saying so.
TEST(SceneFileMissing, DirectoryIsNotAScene) {
  TemporaryDirectory temporary;
  const fs::path directory = temporary.path() / "scene_dir.yaml";
  fs::create_directory(directory);
  Expectation expectation;
  expectation.line_optional = true;
  expectation.fragments = {"directory", "cannot", "not a file", "not a regular file", "unable", "failed"};
  expectOneLineError(directory.string(), {}, expectation, temporary.path(), {});
}

}  // namespace
}  // namespace mbsopt
