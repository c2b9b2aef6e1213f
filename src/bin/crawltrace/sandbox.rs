//! The render sandbox: `crawltrace render` rasterizes in a child process of its own (the same
//! binary, `render --in-sandbox`) under processor-time and memory limits, because usvg and resvg
//! can loop or allocate without bound on small hostile documents in ways no check of the parsed
//! tree can see (an arc of radius 10³⁸ becomes millions of curves while it is parsed). The child
//! reads the SVG text on its standard input and writes PNG bytes on its standard output; it opens
//! no file. Its limits come in two steps: a small budget for parsing, then, once the library has
//! estimated the render ([`crawltrace::prepare_render`]), a budget for that render.
//!
//! Elsewhere than on Unix there are no resource limits, and the render runs in-process with the
//! library's checks alone.

use std::io::{self, Read, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use crawltrace::{prepare_render, RenderOptions};

use crate::exit::Failure;

/// DECISION: processor time for parsing: 2 s, plus 1 s per megabyte of SVG (usvg parses about
/// 10 MB/s on the development machine).
const PARSE_SECONDS: u64 = 2;
const PARSE_BYTES_PER_SECOND: u64 = 1 << 20;

/// DECISION: processor time for rendering: 2 s plus the estimate at a quarter of the measured
/// speed (10⁹ pixel operations a second), plus 1 s per 16 megapixels for the PNG encoding.
const RENDER_SECONDS: f64 = 2.0;
const OPERATIONS_PER_SECOND: f64 = 2.5e8;
const ENCODED_PIXELS_PER_SECOND: f64 = 16e6;

/// DECISION: memory (address space) for the child: 128 MiB for the program itself and its
/// parser, 16 bytes per byte of SVG for the parsed tree, then room for the canvas, its PNG and
/// twice the estimated layers.
const BASE_BYTES: u64 = 128 << 20;
const TREE_BYTES_PER_SVG_BYTE: u64 = 16;
const CANVAS_COPIES: u64 = 3;

/// DECISION: the parent's own deadline, beyond the processor-time limits (which a child waiting
/// on nothing never reaches): 10 minutes.
const WALL_CLOCK_LIMIT: Duration = Duration::from_secs(600);

/// Renders `svg` (the text of `input`) to PNG bytes in the sandbox. Errors name `input`.
pub fn render_sandboxed(
    svg: &[u8],
    input: &Path,
    options: &RenderOptions,
) -> Result<Vec<u8>, Failure> {
    if !cfg!(unix) {
        return render_to_png(svg, options).map_err(|message| Failure::new(input, message));
    }
    let executable = std::env::current_exe()
        .map_err(|e| Failure::new(input, format!("cannot start the renderer: {e}")))?;
    let mut child = Command::new(executable)
        .args(["render", "--in-sandbox", "-", "-o", "-"])
        .arg(format!("--scale={}", options.scale))
        .arg(format!("--max-pixels={}", options.max_pixels))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Failure::new(input, format!("cannot start the renderer: {e}")))?;
    let mut stdin = child.stdin.take().expect("piped");
    let svg = svg.to_vec();
    // Written from a thread: the child may fill its output pipe before it has read all input.
    let feeder = thread::spawn(move || stdin.write_all(&svg));
    let mut stdout = child.stdout.take().expect("piped");
    let reader = thread::spawn(move || {
        let mut png = Vec::new();
        stdout.read_to_end(&mut png).map(|_| png)
    });
    let mut stderr = child.stderr.take().expect("piped");
    let errors = thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });

    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if started.elapsed() < WALL_CLOCK_LIMIT => {
                thread::sleep(Duration::from_millis(5))
            }
            _ => {
                let _ = child.kill();
                break child.wait().map_err(|e| Failure::new(input, e))?;
            }
        }
    };
    // A child that died early closed its input: the feeder's broken pipe is no news.
    let _ = feeder.join();
    let png = reader.join().ok().and_then(Result::ok).unwrap_or_default();
    let errors = errors.join().unwrap_or_default();
    if status.success() {
        return Ok(png);
    }
    Err(Failure::new(input, explain_failure(status, &errors)))
}

/// What a failed child says, in one line.
fn explain_failure(status: std::process::ExitStatus, errors: &str) -> String {
    let said = errors.lines().find(|line| !line.trim().is_empty());
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        match status.signal() {
            Some(SIGXCPU) | Some(SIGKILL) => {
                return "refusing to render: it took longer than its time budget (a construct usvg or resvg cannot render in bounded time)".to_string()
            }
            Some(SIGABRT) if errors.contains("memory allocation") => {
                return "refusing to render: it needed more memory than its budget".to_string()
            }
            Some(SIGABRT) => {
                return "the renderer crashed on it (a bug upstream in usvg or resvg; see the known limits in docs/cli.md)".to_string()
            }
            _ => {}
        }
    }
    match said {
        // The child reports as the command does: `error: <what>`.
        Some(line) => line.trim().trim_start_matches("error: ").to_string(),
        None => format!("the renderer failed ({status})"),
    }
}

#[cfg(unix)]
const SIGXCPU: i32 = 24;
#[cfg(unix)]
const SIGKILL: i32 = 9;
#[cfg(unix)]
const SIGABRT: i32 = 6;

/// The child's side: reads the SVG on standard input, limits itself, renders, and writes the
/// PNG on standard output. A refusal is one line on standard error, then exit status 2.
pub fn serve(options: &RenderOptions) -> Result<(), String> {
    // A panic upstream is caught and reported as one line by the library; its default message
    // on standard error would be taken for that line.
    std::panic::set_hook(Box::new(|_| {}));
    let mut svg = Vec::new();
    io::stdin()
        .read_to_end(&mut svg)
        .map_err(|e| format!("cannot read the SVG: {e}"))?;
    let png = render_to_png(&svg, options)?;
    io::stdout()
        .lock()
        .write_all(&png)
        .map_err(|e| format!("cannot hand over the picture: {e}"))
}

/// Parses, estimates and renders with the limits of each step, and encodes the PNG.
fn render_to_png(svg: &[u8], options: &RenderOptions) -> Result<Vec<u8>, String> {
    let svg_bytes = svg.len() as u64;
    let tree_bytes = BASE_BYTES + TREE_BYTES_PER_SVG_BYTE * svg_bytes;
    limits::set(
        PARSE_SECONDS + svg_bytes / PARSE_BYTES_PER_SECOND,
        tree_bytes,
    );
    let svg = std::str::from_utf8(svg).map_err(|_| "not UTF-8 text".to_string())?;
    let started = Instant::now();
    let prepared = prepare_render(svg, options).map_err(|e| e.to_string())?;
    let (width, height) = prepared.dimensions();
    let canvas = f64::from(width) * f64::from(height);
    let render_seconds = RENDER_SECONDS
        + prepared.operations() / OPERATIONS_PER_SECOND
        + canvas / ENCODED_PIXELS_PER_SECOND;
    let canvas_bytes = u64::from(width) * u64::from(height) * 4;
    let layer_bytes = prepared.layer_bytes().min(u64::MAX as f64) as u64;
    limits::set(
        started.elapsed().as_secs() + PARSE_SECONDS + render_seconds.ceil() as u64,
        tree_bytes
            .saturating_add(CANVAS_COPIES.saturating_mul(canvas_bytes))
            .saturating_add(layer_bytes.saturating_mul(2)),
    );
    let image = prepared.render().map_err(|e| e.to_string())?;
    let mut png = Vec::new();
    image
        .write_to(&mut io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(png)
}

#[cfg(unix)]
mod limits {
    use rustix::process::{getrlimit, setrlimit, Resource, Rlimit};

    /// Limits this process to `seconds` of processor time (then SIGXCPU) and `bytes` of address
    /// space (then allocations fail and the process aborts), never above the hard limits it was
    /// given; a limit that cannot be set is left as it was (the library's own checks still hold).
    pub fn set(seconds: u64, bytes: u64) {
        lower_to(Resource::Cpu, seconds.max(1));
        lower_to(Resource::As, bytes);
    }

    fn lower_to(resource: Resource, wanted: u64) {
        let old = getrlimit(resource);
        let cap = |limit: Option<u64>| limit.map_or(wanted, |limit| limit.min(wanted));
        // The soft limit may be raised again later (the render step gets more than parsing),
        // up to the hard limit, which stays where it was.
        let _ = setrlimit(
            resource,
            Rlimit {
                current: Some(cap(old.maximum)),
                maximum: old.maximum,
            },
        );
    }
}

#[cfg(not(unix))]
mod limits {
    /// No resource limits outside Unix.
    pub fn set(_seconds: u64, _bytes: u64) {}
}
