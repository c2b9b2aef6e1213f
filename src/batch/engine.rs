//! Batch tracing of image folders: finds the inputs, maps each to its output path, runs a per-file
//! processor over them in parallel, and reports (progress bar, error lines, summary, JSON Lines).
//!
//! The engine knows nothing about tracing: it takes any `Fn(&Path) -> Result<FileResult, String>`,
//! so the real tracer and the test and benchmark fakes go through the same code.
//!
//! Rules it keeps (see `../shared/DESIGN.md`, "Command line"):
//! - the output of `x/y.png` under a folder input is `OUT/x/y.svg`; two inputs with the same output
//!   are an error before any work starts;
//! - an input is never overwritten, and outputs are written whole ([`write_atomically`]);
//! - an output file at least as new as its input is up to date and skipped unless `force`;
//! - a failing file never stops the batch; it is reported and counted, and makes the exit status 1;
//! - [`Shard`]s split the inputs by a stable hash of their relative paths, so several machines can
//!   share one batch without talking to each other.

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::fs;
use std::io::{self, IsTerminal, Write};
use std::panic::{self, AssertUnwindSafe};
use std::path::{Component, Path, PathBuf};
use std::str::FromStr;
use std::time::{Duration, Instant};

use globset::{GlobBuilder, GlobMatcher};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use walkdir::WalkDir;

/// File extensions (lower case, without the dot) of the formats the `image` crate reads with the
/// decoders this crate enables. Files found in folders are taken only with one of these.
pub const IMAGE_EXTENSIONS: &[&str] = &[
    "png", "jpg", "jpeg", "gif", "bmp", "tif", "tiff", "webp", "pbm", "pgm", "ppm", "pnm", "pam",
    "tga", "ico", "qoi", "hdr", "dds", "exr", "ff",
];

/// Whether `path` ends in one of the [`IMAGE_EXTENSIONS`], in any letter case.
pub fn is_image_path(path: &Path) -> bool {
    path.extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| {
            IMAGE_EXTENSIONS
                .iter()
                .any(|known| known.eq_ignore_ascii_case(extension))
        })
}

/// What the per-file processor returns for one image.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileResult {
    /// The SVG document to write.
    pub svg: Vec<u8>,
    /// How many curves it holds.
    pub curves: usize,
    /// How many of them are closed.
    pub closed_curves: usize,
}

/// How a batch runs. `Default` is: top level of folders only, every image, all cores, resumable,
/// progress shown on a terminal, no shard, no report.
#[derive(Clone, Debug, Default)]
pub struct BatchOptions {
    /// Scan folders recursively instead of their top level only.
    pub recursive: bool,
    /// Take only the files of folder inputs that match this glob. A pattern without `/` is
    /// matched against the file name (`scan-*`), one with `/` against the path relative to the
    /// folder given (`**/*.png`, `2024/*.jpg`); `*` never crosses a `/`. Case-sensitive.
    pub glob: Option<String>,
    /// Worker threads; `None` is one per core (or `RAYON_NUM_THREADS`).
    pub jobs: Option<usize>,
    /// Redo files whose output is already up to date.
    pub force: bool,
    /// No progress bar, warnings or summary; failures are still printed.
    pub quiet: bool,
    /// Process only this shard of the inputs.
    pub shard: Option<Shard>,
    /// Write a JSON Lines report here at the end, one object per input.
    pub report: Option<PathBuf>,
}

/// Shard `index` of `count` (both counted from 1): the inputs whose relative path hashes to it.
///
/// A file belongs to shard K of N iff the FNV-1a 64-bit hash of its relative path (UTF-8 bytes,
/// `/` between components) modulo N equals K − 1. The hash is fixed, unlike `std`'s randomised
/// one, so every machine and every run agrees, and shards 1/N … N/N partition the inputs exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, from 1 to `count`.
    pub index: u64,
    /// How many shards there are, at least 1.
    pub count: u64,
}

/// Why a shard description like `2/5` was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not two whole numbers separated by `/`.
    #[error("expected K/N (shard K of N, like 2/5), found {0:?}")]
    Syntax(String),
    /// N is 0.
    #[error("the number of shards must be at least 1")]
    NoShards,
    /// K is 0 or greater than N.
    #[error("shard {index} of {count} does not exist: K must be between 1 and {count}")]
    OutOfRange {
        /// The K given.
        index: u64,
        /// The N given.
        count: u64,
    },
}

impl Shard {
    /// Shard `index` of `count`, checked: 1 ≤ `index` ≤ `count`.
    pub fn new(index: u64, count: u64) -> Result<Self, ShardError> {
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if index == 0 || index > count {
            return Err(ShardError::OutOfRange { index, count });
        }
        Ok(Self { index, count })
    }

    /// Whether the input with this relative path belongs to this shard.
    pub fn contains(&self, relative: &Path) -> bool {
        fnv1a_64(&shard_key(relative)) % self.count == self.index - 1
    }
}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Self, ShardError> {
        let syntax = || ShardError::Syntax(text.to_string());
        let (index, count) = text.split_once('/').ok_or_else(syntax)?;
        // `u64::from_str` accepts a leading `+`; a shard number is plain digits.
        let number = |part: &str| {
            if part.is_empty() || !part.bytes().all(|byte| byte.is_ascii_digit()) {
                return Err(syntax());
            }
            part.parse::<u64>().map_err(|_| syntax())
        };
        Self::new(number(index)?, number(count)?)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}/{}", self.index, self.count)
    }
}

/// The 64-bit FNV-1a hash of `bytes`.
pub fn fnv1a_64(bytes: &[u8]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET_BASIS, |hash, &byte| {
        (hash ^ u64::from(byte)).wrapping_mul(PRIME)
    })
}

/// The bytes a relative path is hashed by: its components joined with `/` whatever the platform,
/// so that a shard holds the same files on Windows and Unix.
fn shard_key(relative: &Path) -> Vec<u8> {
    let mut key = Vec::new();
    for component in relative.components() {
        if let Component::Normal(name) = component {
            if !key.is_empty() {
                key.push(b'/');
            }
            key.extend_from_slice(os_bytes(name).as_ref());
        }
    }
    key
}

#[cfg(unix)]
fn os_bytes(name: &std::ffi::OsStr) -> std::borrow::Cow<'_, [u8]> {
    use std::os::unix::ffi::OsStrExt;
    std::borrow::Cow::Borrowed(name.as_bytes())
}

#[cfg(not(unix))]
fn os_bytes(name: &std::ffi::OsStr) -> std::borrow::Cow<'_, [u8]> {
    match name.to_string_lossy() {
        std::borrow::Cow::Borrowed(text) => std::borrow::Cow::Borrowed(text.as_bytes()),
        std::borrow::Cow::Owned(text) => std::borrow::Cow::Owned(text.into_bytes()),
    }
}

/// One input of a batch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Input {
    /// The file as it can be opened: the folder given joined with `relative`, or the file given.
    pub source: PathBuf,
    /// Its path relative to the folder given, or its file name if it was given itself. The output
    /// mirrors it, and shards are decided by it.
    pub relative: PathBuf,
    /// Set when the folder scan could not read this entry (a broken symbolic link, a subfolder
    /// without permission); it is then reported as failed without being processed.
    pub unreadable: Option<String>,
    /// `source` with every symbolic link resolved, when that succeeded.
    canonical: Option<PathBuf>,
}

impl Input {
    /// Where the output goes, relative to the output folder: `relative` with the extension `svg`.
    pub fn output_relative(&self) -> PathBuf {
        self.relative.with_extension("svg")
    }
}

/// The inputs of a batch, found by [`discover_inputs`].
#[derive(Clone, Debug, Default)]
pub struct Discovery {
    /// The inputs of the requested shard, sorted by relative path.
    pub inputs: Vec<Input>,
    /// Files in the folders that were left out because they have no image extension.
    pub not_images: usize,
    /// Files in the folders that were left out because they do not match the glob.
    pub excluded_by_glob: usize,
    /// Inputs that belong to other shards.
    pub in_other_shards: usize,
    /// Things worth saying that are not failures, each `<path>: <what>` (symbolic link loops).
    pub warnings: Vec<String>,
    /// Canonical paths of every input of every shard: no output may land on one of them.
    protected: HashSet<PathBuf>,
}

/// An error that stops a batch before (or, for the report, after) the per-file work. Its text is
/// `<file>: <what>`, to be printed as `error: <file>: <what>` with exit status 2.
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// An input named on the command line cannot be read.
    #[error("{}: {}", path.display(), describe_io(source))]
    Input {
        /// The input as given.
        path: PathBuf,
        /// What went wrong.
        source: io::Error,
    },
    /// The glob does not parse.
    #[error("--glob {pattern:?}: {message}")]
    Glob {
        /// The pattern as given.
        pattern: String,
        /// What is wrong with it.
        message: String,
    },
    /// Two inputs would be written to the same output.
    #[error("{}: both {} and {} would be written to this output", output.display(), first.display(), second.display())]
    OutputCollision {
        /// The shared output, relative to the output folder.
        output: PathBuf,
        /// The first input, in sorted order.
        first: PathBuf,
        /// The second input.
        second: PathBuf,
    },
    /// `jobs` is 0.
    #[error("--jobs: at least one worker thread is needed")]
    NoJobs,
    /// The worker threads could not be started.
    #[error("worker threads: {0}")]
    ThreadPool(String),
    /// The output folder cannot be created.
    #[error("{}: cannot create the output folder: {message}", path.display())]
    OutputFolder {
        /// The output folder.
        path: PathBuf,
        /// Why not.
        message: String,
    },
    /// The report cannot be written.
    #[error("{}: cannot write the report: {message}", path.display())]
    Report {
        /// The report file.
        path: PathBuf,
        /// Why not.
        message: String,
    },
}

/// Finds the inputs: files named directly are always taken; folders are scanned (recursively if
/// `options.recursive`) for files with an image extension that match `options.glob`. Symbolic
/// links are followed; a link back to a folder being scanned is reported in
/// [`Discovery::warnings`] and not followed again. The result is sorted by relative path, the same
/// file reached twice under the same relative path is kept once, and only `options.shard` is kept.
///
/// Errors: an input that does not exist or cannot be read, a bad glob, or two inputs with the same
/// output (checked across all shards, since they would share the output folder).
pub fn discover_inputs(
    inputs: &[PathBuf],
    options: &BatchOptions,
) -> Result<Discovery, BatchError> {
    let glob = options.glob.as_deref().map(compile_glob).transpose()?;
    let mut discovery = Discovery::default();
    let mut found = Vec::new();
    for input in inputs {
        let metadata = fs::metadata(input).map_err(|source| BatchError::Input {
            path: input.clone(),
            source,
        })?;
        if metadata.is_dir() {
            // Fail early on a folder we cannot list rather than report it as one bad entry.
            fs::read_dir(input).map_err(|source| BatchError::Input {
                path: input.clone(),
                source,
            })?;
            scan_folder(
                input,
                options.recursive,
                glob.as_ref(),
                &mut discovery,
                &mut found,
            );
        } else {
            let Some(name) = input.file_name() else {
                return Err(BatchError::Input {
                    path: input.clone(),
                    source: io::Error::other("not a file name"),
                });
            };
            found.push(new_input(input.clone(), PathBuf::from(name), None));
        }
    }

    found.sort_by(|a, b| (&a.relative, &a.source).cmp(&(&b.relative, &b.source)));
    // The same file reached twice (a folder and a file in it, a folder given twice) is one input.
    found.dedup_by(|later, earlier| {
        later.relative == earlier.relative
            && later.canonical.is_some()
            && later.canonical == earlier.canonical
    });

    let mut outputs: HashMap<PathBuf, &Input> = HashMap::new();
    for input in found.iter().filter(|input| input.unreadable.is_none()) {
        if let Some(first) = outputs.insert(input.output_relative(), input) {
            return Err(BatchError::OutputCollision {
                output: input.output_relative(),
                first: first.source.clone(),
                second: input.source.clone(),
            });
        }
    }

    discovery.protected = found
        .iter()
        .filter_map(|input| input.canonical.clone())
        .collect();
    let total = found.len();
    discovery.inputs = match options.shard {
        Some(shard) => found
            .into_iter()
            .filter(|input| shard.contains(&input.relative))
            .collect(),
        None => found,
    };
    discovery.in_other_shards = total - discovery.inputs.len();
    Ok(discovery)
}

fn new_input(source: PathBuf, relative: PathBuf, unreadable: Option<String>) -> Input {
    let canonical = fs::canonicalize(&source).ok();
    Input {
        source,
        relative,
        unreadable,
        canonical,
    }
}

/// A compiled `--glob`, with the rule for what it is matched against.
struct Filter {
    matcher: GlobMatcher,
    /// The pattern has no `/`: match the file name, wherever the file is.
    file_name_only: bool,
}

impl Filter {
    fn matches(&self, relative: &Path) -> bool {
        if self.file_name_only {
            relative
                .file_name()
                .is_some_and(|name| self.matcher.is_match(name))
        } else {
            // Match with `/` separators on every platform, like the shard key.
            self.matcher
                .is_match(String::from_utf8_lossy(&shard_key(relative)).as_ref())
        }
    }
}

fn compile_glob(pattern: &str) -> Result<Filter, BatchError> {
    let glob = GlobBuilder::new(pattern)
        .literal_separator(true)
        .build()
        .map_err(|error| BatchError::Glob {
            pattern: pattern.to_string(),
            message: error.kind().to_string(),
        })?;
    Ok(Filter {
        matcher: glob.compile_matcher(),
        file_name_only: !pattern.contains('/'),
    })
}

fn scan_folder(
    root: &Path,
    recursive: bool,
    glob: Option<&Filter>,
    discovery: &mut Discovery,
    found: &mut Vec<Input>,
) {
    let walker = WalkDir::new(root)
        .follow_links(true)
        .min_depth(1)
        .max_depth(if recursive { usize::MAX } else { 1 })
        .sort_by_file_name();
    // Whether a file passes the glob and the extension test, counting those that do not.
    let wanted = |relative: &Path, discovery: &mut Discovery| {
        if glob.is_some_and(|glob| !glob.matches(relative)) {
            discovery.excluded_by_glob += 1;
            false
        } else if !is_image_path(relative) {
            discovery.not_images += 1;
            false
        } else {
            true
        }
    };
    for entry in walker {
        match entry {
            Ok(entry) => {
                if entry.file_type().is_dir() {
                    continue;
                }
                let relative = relative_to(entry.path(), root);
                if wanted(&relative, discovery) {
                    found.push(new_input(entry.path().to_path_buf(), relative, None));
                }
            }
            Err(error) => {
                let path = error.path().unwrap_or(root).to_path_buf();
                if let Some(ancestor) = error.loop_ancestor() {
                    // Everything behind the link is scanned through its real place already.
                    discovery.warnings.push(format!(
                        "{}: symbolic link loop back to {}, not followed",
                        path.display(),
                        ancestor.display()
                    ));
                    continue;
                }
                let relative = relative_to(&path, root);
                if relative.as_os_str().is_empty() {
                    continue; // the root itself, checked readable by the caller
                }
                let link_or_file = fs::symlink_metadata(&path);
                let is_folder = link_or_file.as_ref().is_ok_and(|m| m.is_dir());
                // A file we cannot reach is reported only if it would have been taken.
                if !is_folder && !wanted(&relative, discovery) {
                    continue;
                }
                let message = match error.io_error() {
                    Some(io_error)
                        if io_error.kind() == io::ErrorKind::NotFound
                            && link_or_file.is_ok_and(|m| m.file_type().is_symlink()) =>
                    {
                        "broken symbolic link".to_string()
                    }
                    Some(io_error) if is_folder => {
                        format!("cannot read this folder: {}", describe_io(io_error))
                    }
                    Some(io_error) => describe_io(io_error),
                    None => error.to_string(),
                };
                found.push(new_input(path, relative, Some(message)));
            }
        }
    }
}

fn relative_to(path: &Path, root: &Path) -> PathBuf {
    path.strip_prefix(root).unwrap_or(path).to_path_buf()
}

/// What happened to one input.
#[derive(Clone, Debug, PartialEq)]
pub enum FileStatus {
    /// Traced and written.
    Done {
        /// Curves in the output.
        curves: usize,
        /// Closed curves among them.
        closed_curves: usize,
        /// Time spent processing it, writing included.
        seconds: f64,
    },
    /// The output was already up to date.
    Skipped,
    /// Not done; the batch went on.
    Failed {
        /// Why, on one line.
        message: String,
        /// Time spent processing it, when the processor ran.
        seconds: Option<f64>,
    },
}

/// One input and what happened to it.
#[derive(Clone, Debug, PartialEq)]
pub struct FileOutcome {
    /// The input file.
    pub source: PathBuf,
    /// Its path relative to the folder given.
    pub relative: PathBuf,
    /// Its output, `None` for an entry the folder scan could not read.
    pub output: Option<PathBuf>,
    /// What happened.
    pub status: FileStatus,
}

/// The result of [`run_batch`].
#[derive(Clone, Debug, Default)]
pub struct BatchSummary {
    /// One outcome per input, in the order of [`Discovery::inputs`] (sorted by relative path).
    pub outcomes: Vec<FileOutcome>,
    /// Inputs traced and written.
    pub done: usize,
    /// Inputs skipped because their output was up to date.
    pub skipped: usize,
    /// Inputs that failed.
    pub failed: usize,
    /// Files in the folders without an image extension.
    pub not_images: usize,
    /// Inputs left to other shards.
    pub in_other_shards: usize,
    /// Wall-clock time of the whole run.
    pub elapsed: Duration,
}

impl BatchSummary {
    /// The process exit status: 1 if any input failed, else 0.
    pub fn exit_code(&self) -> u8 {
        u8::from(self.failed > 0)
    }

    /// The report: one JSON object a line per input, in input order, with the fields `path`,
    /// `output`, `status` (`done`, `skipped` or `failed`), `curves`, `closed_curves`, `seconds`
    /// and `error`; fields that do not apply are `null`.
    pub fn report_json_lines(&self) -> String {
        let mut text = String::new();
        for outcome in &self.outcomes {
            let (status, curves, closed_curves, seconds, error) = match &outcome.status {
                FileStatus::Done {
                    curves,
                    closed_curves,
                    seconds,
                } => (
                    "done",
                    Some(*curves),
                    Some(*closed_curves),
                    Some(*seconds),
                    None,
                ),
                FileStatus::Skipped => ("skipped", None, None, None, None),
                FileStatus::Failed { message, seconds } => {
                    ("failed", None, None, *seconds, Some(message.as_str()))
                }
            };
            let line = ReportLine {
                path: outcome.source.to_string_lossy(),
                output: outcome.output.as_ref().map(|path| path.to_string_lossy()),
                status,
                curves,
                closed_curves,
                seconds,
                error,
            };
            // Serialising strings, numbers and nulls cannot fail.
            if let Ok(json) = serde_json::to_string(&line) {
                text.push_str(&json);
                text.push('\n');
            }
        }
        text
    }
}

impl fmt::Display for BatchSummary {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            formatter,
            "{} done, {} skipped (up to date), {} failed",
            self.done, self.skipped, self.failed
        )?;
        if self.not_images > 0 {
            write!(formatter, ", {} not images", self.not_images)?;
        }
        if self.in_other_shards > 0 {
            write!(formatter, ", {} in other shards", self.in_other_shards)?;
        }
        write!(formatter, " ({:.1} s)", self.elapsed.as_secs_f64())
    }
}

#[derive(serde::Serialize)]
struct ReportLine<'a> {
    path: std::borrow::Cow<'a, str>,
    output: Option<std::borrow::Cow<'a, str>>,
    status: &'static str,
    curves: Option<usize>,
    closed_curves: Option<usize>,
    seconds: Option<f64>,
    error: Option<&'a str>,
}

/// Runs `process` over the inputs of `discovery` on `options.jobs` threads and writes each result
/// to `out_dir`, mirroring the relative paths (folders are created as needed).
///
/// Per file, in order: an output that would land on an input is refused; an output file at least
/// as new as its input is skipped unless `options.force`; otherwise `process` runs (a panic in it is
/// caught and counted as a failure) and its SVG is written with [`write_atomically`]. Failures are
/// printed as `error: <input>: <message>` as they happen and never stop the batch. A progress bar
/// is drawn on stderr when it is a terminal and not `options.quiet`; a summary line ends the run
/// unless quiet. The report, if asked for, is written at the end.
///
/// Errors (before any work): `jobs` of 0, an output folder that cannot be created, a report whose
/// folder does not exist (other than `out_dir`, which the run makes) or that would overwrite an
/// input; (after the work) a report that cannot
/// be written.
pub fn run_batch<F>(
    discovery: &Discovery,
    out_dir: &Path,
    options: &BatchOptions,
    process: F,
) -> Result<BatchSummary, BatchError>
where
    F: Fn(&Path) -> Result<FileResult, String> + Sync,
{
    let started = Instant::now();
    if options.jobs == Some(0) {
        return Err(BatchError::NoJobs);
    }
    if let Some(report) = &options.report {
        check_report_path(report, out_dir, &discovery.protected)?;
    }
    fs::create_dir_all(out_dir).map_err(|error| BatchError::OutputFolder {
        path: out_dir.to_path_buf(),
        message: match error.kind() {
            io::ErrorKind::AlreadyExists => "a file is in the way".to_string(),
            _ => describe_io(&error),
        },
    })?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.unwrap_or(0))
        .build()
        .map_err(|error| BatchError::ThreadPool(error.to_string()))?;

    let console = Console::new(discovery.inputs.len(), options.quiet);
    if !options.quiet {
        for warning in &discovery.warnings {
            console.line(&format!("warning: {warning}"));
        }
    }
    // An indexed parallel iterator collects in input order, whatever order the files finish in.
    let outcomes: Vec<FileOutcome> = pool.install(|| {
        discovery
            .inputs
            .par_iter()
            .map(|input| {
                let outcome = process_one(input, out_dir, options.force, discovery, &process);
                if let FileStatus::Failed { message, .. } = &outcome.status {
                    console.line(&failure_line(&outcome.source, message));
                }
                console.advance();
                outcome
            })
            .collect()
    });
    console.finish();

    let count = |wanted: fn(&FileStatus) -> bool| {
        outcomes
            .iter()
            .filter(|outcome| wanted(&outcome.status))
            .count()
    };
    let mut summary = BatchSummary {
        done: count(|status| matches!(status, FileStatus::Done { .. })),
        skipped: count(|status| matches!(status, FileStatus::Skipped)),
        failed: count(|status| matches!(status, FileStatus::Failed { .. })),
        not_images: discovery.not_images,
        in_other_shards: discovery.in_other_shards,
        outcomes,
        elapsed: Duration::ZERO,
    };
    if let Some(report) = &options.report {
        write_atomically(report, summary.report_json_lines().as_bytes()).map_err(|error| {
            BatchError::Report {
                path: report.clone(),
                message: describe_io(&error),
            }
        })?;
    }
    summary.elapsed = started.elapsed();
    if !options.quiet {
        eprintln!("{summary}");
    }
    Ok(summary)
}

fn check_report_path(
    report: &Path,
    out_dir: &Path,
    protected: &HashSet<PathBuf>,
) -> Result<(), BatchError> {
    let refuse = |message: &str| BatchError::Report {
        path: report.to_path_buf(),
        message: message.to_string(),
    };
    let folder = parent_folder(report);
    // The output folder is the natural place for the report, and the run creates it; a first
    // run must not refuse what every later run accepts.
    let in_out_dir = without_current_dir(folder).eq(without_current_dir(out_dir));
    if !folder.is_dir() && !in_out_dir {
        return Err(refuse("its folder does not exist"));
    }
    if lands_on_protected(report, protected) {
        return Err(refuse("refusing to overwrite an input"));
    }
    Ok(())
}

/// The components of `path` without its `.`s, so that `./out` and `out` compare equal.
fn without_current_dir(path: &Path) -> impl Iterator<Item = Component<'_>> {
    path.components()
        .filter(|component| *component != Component::CurDir)
}

/// The folder a file path lives in; `.` for a bare file name.
fn parent_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// Whether writing `path` would replace one of the `protected` files, symbolic links resolved.
fn lands_on_protected(path: &Path, protected: &HashSet<PathBuf>) -> bool {
    let resolved = fs::canonicalize(path).ok().or_else(|| {
        // Not there yet: it can only land on an input through a linked folder.
        let folder = fs::canonicalize(parent_folder(path)).ok()?;
        Some(folder.join(path.file_name()?))
    });
    resolved.is_some_and(|resolved| protected.contains(&resolved))
}

fn process_one<F>(
    input: &Input,
    out_dir: &Path,
    force: bool,
    discovery: &Discovery,
    process: &F,
) -> FileOutcome
where
    F: Fn(&Path) -> Result<FileResult, String> + Sync,
{
    let (output, status) = match &input.unreadable {
        Some(message) => (
            None,
            FileStatus::Failed {
                message: message.clone(),
                seconds: None,
            },
        ),
        None => {
            let output = out_dir.join(input.output_relative());
            let status = trace_one(input, &output, force, discovery, process);
            (Some(output), status)
        }
    };
    FileOutcome {
        source: input.source.clone(),
        relative: input.relative.clone(),
        output,
        status,
    }
}

fn trace_one<F>(
    input: &Input,
    output: &Path,
    force: bool,
    discovery: &Discovery,
    process: &F,
) -> FileStatus
where
    F: Fn(&Path) -> Result<FileResult, String> + Sync,
{
    let failed = |message: String, seconds: Option<f64>| FileStatus::Failed { message, seconds };
    // Checked before the up-to-date test: an output that *is* its input always looks up to date.
    if lands_on_protected(output, &discovery.protected) {
        return failed(
            format!("refusing to overwrite an input with {}", output.display()),
            None,
        );
    }
    let input_modified = match fs::metadata(&input.source).and_then(|m| m.modified()) {
        Ok(modified) => modified,
        Err(error) => return failed(describe_io(&error), None),
    };
    if !force {
        // Only a file is an output: a folder (or anything else) in its place is not up to date,
        // and writing there then fails with a message instead of the file being skipped quietly.
        let output_modified = fs::metadata(output)
            .ok()
            .filter(|metadata| metadata.is_file())
            .and_then(|metadata| metadata.modified().ok());
        if output_modified.is_some_and(|modified| modified >= input_modified) {
            return FileStatus::Skipped;
        }
    }

    let started = Instant::now();
    let seconds = || started.elapsed().as_secs_f64();
    // A bug in the processor on one odd file must not take the other thousands down with it.
    let result = match panic::catch_unwind(AssertUnwindSafe(|| process(&input.source))) {
        Ok(Ok(result)) => result,
        Ok(Err(message)) => return failed(message, Some(seconds())),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|text| text.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".to_string());
            return failed(format!("internal error: {what}"), Some(seconds()));
        }
    };
    let folder = parent_folder(output);
    if let Err(error) = fs::create_dir_all(folder) {
        return failed(
            format!(
                "cannot create the folder {}: {}",
                folder.display(),
                describe_io(&error)
            ),
            Some(seconds()),
        );
    }
    if let Err(error) = write_atomically(output, &result.svg) {
        return failed(
            format!("cannot write {}: {}", output.display(), describe_io(&error)),
            Some(seconds()),
        );
    }
    FileStatus::Done {
        curves: result.curves,
        closed_curves: result.closed_curves,
        seconds: seconds(),
    }
}

/// `error: <path>: <message>`, on a single line whatever the message holds.
fn failure_line(path: &Path, message: &str) -> String {
    let message: String = message
        .trim()
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect();
    format!("error: {}: {}", path.display(), message)
}

/// Where progress and messages go: through the bar while it is drawn, so lines do not tear it.
struct Console {
    bar: Option<ProgressBar>,
}

impl Console {
    fn new(total: usize, quiet: bool) -> Self {
        if quiet || !io::stderr().is_terminal() {
            return Self { bar: None };
        }
        let bar = ProgressBar::new(total as u64);
        if let Ok(style) = ProgressStyle::with_template(
            // `per_sec:1`: one decimal (the width field sets the precision for rates).
            "{wide_bar} {pos}/{len} files  {per_sec:1}  {elapsed} elapsed, ETA {eta}",
        ) {
            bar.set_style(style);
        }
        Self { bar: Some(bar) }
    }

    fn line(&self, text: &str) {
        match &self.bar {
            Some(bar) => bar.println(text),
            None => eprintln!("{text}"),
        }
    }

    fn advance(&self) {
        if let Some(bar) = &self.bar {
            bar.inc(1);
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// A short description of an I/O error, without Rust's `(os error N)` suffix.
pub fn describe_io(error: &io::Error) -> String {
    match error.kind() {
        io::ErrorKind::NotFound => "no such file".to_string(),
        io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        io::ErrorKind::IsADirectory => "is a folder, not a file".to_string(),
        _ => {
            let text = error.to_string();
            match text.find(" (os error") {
                Some(cut) => text[..cut].to_string(),
                None => text,
            }
        }
    }
}

/// Writes `bytes` to `path` whole: into a temporary file in the same folder, flushed to disk,
/// then renamed over `path`. A reader, or a run interrupted at any point, sees the old file or
/// the new one, never a part; an interrupted run may leave a hidden `.crawltrace-*.tmp` file, never
/// a truncated file under the real name. The folder must exist.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut temporary = temporary_file_beside(path)?;
    temporary.write_all(bytes)?;
    // Without this a crash soon after the rename can leave an empty file under the real name,
    // which a resumed batch would then take for an up-to-date output.
    temporary.as_file().sync_all()?;
    temporary.persist(path).map_err(|error| error.error)?;
    Ok(())
}

/// A new temporary file in the folder of `path`, named so that nothing mistakes it for an output
/// or an input: hidden, ending in `.tmp`.
fn temporary_file_beside(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".crawltrace-").suffix(".tmp");
    // tempfile creates files readable by the owner only; an output should get the usual
    // permissions, as from `File::create` (the umask still applies).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(parent_folder(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_64_matches_the_published_test_vectors() {
        assert_eq!(fnv1a_64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a_64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a_64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn shard_key_joins_components_with_slashes() {
        let relative: PathBuf = ["scans", "2024", "a.png"].iter().collect();
        assert_eq!(shard_key(&relative), b"scans/2024/a.png");
        assert_eq!(shard_key(Path::new("a.png")), b"a.png");
    }

    #[test]
    fn shards_parse_from_k_of_n() {
        assert_eq!("2/3".parse(), Ok(Shard { index: 2, count: 3 }));
        assert_eq!("1/1".parse(), Ok(Shard { index: 1, count: 1 }));
        assert_eq!(
            Shard::new(3, 3).map(|shard| shard.to_string()),
            Ok("3/3".into())
        );
    }

    #[test]
    fn bad_shards_are_refused_with_a_reason() {
        assert_eq!(
            "0/3".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 0, count: 3 })
        );
        assert_eq!(
            "4/3".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 4, count: 3 })
        );
        assert_eq!("1/0".parse::<Shard>(), Err(ShardError::NoShards));
        for text in [
            "", "3", "1/", "/3", "a/3", "1/2/3", " 1/3", "+1/3", "-1/3", "1.0/3",
        ] {
            assert_eq!(
                text.parse::<Shard>(),
                Err(ShardError::Syntax(text.to_string())),
                "{text:?}"
            );
        }
        let message = "5/4".parse::<Shard>().unwrap_err().to_string();
        assert!(message.contains("between 1 and 4"), "{message}");
    }

    /// Pinned values (computed apart, in Python): machines running different builds must agree.
    #[test]
    fn shard_membership_is_the_documented_hash() {
        let nested: PathBuf = ["scans", "2024", "a.png"].iter().collect();
        for (relative, count, index) in [
            (Path::new("a.png"), 3, 3),
            (Path::new("a.png"), 7, 5),
            (nested.as_path(), 3, 1),
            (nested.as_path(), 7, 2),
        ] {
            assert!(
                Shard { index, count }.contains(relative),
                "{} should be in {index}/{count}",
                relative.display()
            );
        }
    }

    #[test]
    fn every_path_is_in_exactly_one_shard() {
        for count in 1..=5 {
            for number in 0..200 {
                let relative = PathBuf::from(format!("folder/scan-{number}.png"));
                let owners = (1..=count)
                    .filter(|&index| Shard { index, count }.contains(&relative))
                    .count();
                assert_eq!(owners, 1, "{} in {count} shards", relative.display());
            }
        }
    }

    #[test]
    fn image_extensions_are_recognised_in_any_case() {
        for name in [
            "a.png",
            "b.JPG",
            "c.Jpeg",
            "d.tiff",
            "e.qoi",
            "f.ff",
            "dir/g.WebP",
        ] {
            assert!(is_image_path(Path::new(name)), "{name}");
        }
        for name in ["a.svg", "b.txt", "png", "c.png.bak", ".png", "d"] {
            assert!(!is_image_path(Path::new(name)), "{name}");
        }
    }

    #[test]
    fn a_glob_without_slash_matches_file_names_anywhere() {
        let glob = compile_glob("scan-*").unwrap();
        assert!(glob.matches(Path::new("scan-1.png")));
        assert!(glob.matches(Path::new("deep/er/scan-2.png")));
        assert!(!glob.matches(Path::new("scan-dir/other.png")));
    }

    #[test]
    fn a_glob_with_slash_matches_the_relative_path() {
        let everywhere = compile_glob("**/*.png").unwrap();
        assert!(everywhere.matches(Path::new("top.png")));
        assert!(everywhere.matches(Path::new("a/b/deep.png")));
        assert!(!everywhere.matches(Path::new("a/b/deep.jpg")));
        let one_level = compile_glob("2024/*.png").unwrap();
        assert!(one_level.matches(Path::new("2024/a.png")));
        assert!(
            !one_level.matches(Path::new("2024/sub/a.png")),
            "`*` crossed a `/`"
        );
        assert!(!one_level.matches(Path::new("a.png")));
    }

    #[test]
    fn a_bad_glob_is_an_error() {
        let error = compile_glob("scan-[")
            .err()
            .expect("an unclosed class must be refused");
        assert!(
            error.to_string().starts_with("--glob \"scan-[\": "),
            "{error}"
        );
    }

    #[test]
    fn failure_lines_are_single_lines() {
        let line = failure_line(Path::new("in/a.png"), "first\nsecond\r\nthird\n");
        assert_eq!(line, "error: in/a.png: first second  third");
    }

    #[test]
    fn exit_code_is_one_only_with_failures() {
        let mut summary = BatchSummary {
            done: 3,
            skipped: 2,
            ..BatchSummary::default()
        };
        assert_eq!(summary.exit_code(), 0);
        summary.failed = 1;
        assert_eq!(summary.exit_code(), 1);
    }

    #[test]
    fn summary_line_counts_everything() {
        let summary = BatchSummary {
            done: 3,
            skipped: 2,
            failed: 1,
            not_images: 4,
            in_other_shards: 5,
            ..BatchSummary::default()
        };
        assert_eq!(
            summary.to_string(),
            "3 done, 2 skipped (up to date), 1 failed, 4 not images, 5 in other shards (0.0 s)"
        );
    }

    /// A run killed between creating the temporary file and renaming it leaves the temporary
    /// file behind (nothing gets to delete it); it must not look like an output or an input.
    #[test]
    fn an_interrupted_write_leaves_no_svg() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("drawing.svg");
        let mut temporary = temporary_file_beside(&output).unwrap();
        temporary.write_all(b"<svg xmlns=").unwrap(); // cut short
        let (_, left_behind) = temporary.keep().unwrap(); // as if killed before the rename

        assert!(!output.exists());
        let names: Vec<String> = fs::read_dir(folder.path())
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
        assert!(!names[0].ends_with(".svg"), "{names:?}");
        assert!(!is_image_path(&left_behind), "{names:?}");

        // The next attempt writes the whole file under the real name.
        write_atomically(&output, b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>").unwrap();
        assert_eq!(
            fs::read(&output).unwrap(),
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>"
        );
    }

    #[test]
    fn write_atomically_replaces_a_file_whole() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("a.svg");
        fs::write(&output, "old and longer than the new content").unwrap();
        write_atomically(&output, b"new").unwrap();
        assert_eq!(fs::read(&output).unwrap(), b"new");
        assert_eq!(
            fs::read_dir(folder.path()).unwrap().count(),
            1,
            "a temporary file was left"
        );
    }

    #[cfg(unix)]
    #[test]
    fn write_atomically_gives_the_usual_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let folder = tempfile::tempdir().unwrap();
        let reference = folder.path().join("reference");
        fs::File::create(&reference).unwrap();
        let output = folder.path().join("a.svg");
        write_atomically(&output, b"<svg/>").unwrap();
        let mode = |path: &Path| fs::metadata(path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&output), mode(&reference));
    }
}
