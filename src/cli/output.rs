//! What every subcommand shares to end: the failure and its exit code, and the writing of
//! its output (text, JSON, a glTF file).

/// Why a command failed, and the exit code that says so.
pub struct Failure {
    /// Process exit code: 1 no answer, 2 invalid input.
    pub code: u8,
    /// The message chain.
    pub error: anyhow::Error,
}

impl Failure {
    /// The input (a file or an argument) is invalid.
    pub fn input(error: impl Into<anyhow::Error>) -> Self {
        Failure {
            code: 2,
            error: error.into(),
        }
    }

    /// The input is valid but the problem has no answer.
    pub fn unsolved(error: impl Into<anyhow::Error>) -> Self {
        Failure {
            code: 1,
            error: error.into(),
        }
    }
}

/// Prints a value as pretty JSON on standard output.
pub fn print_json(value: &impl serde::Serialize) -> Result<(), Failure> {
    let text = cable_dict::json::to_pretty_string(value)
        .map_err(|e| Failure::unsolved(anyhow::anyhow!("cannot encode the JSON output: {e}")))?;
    emit(&(text + "\n"))
}

/// Writes a command's whole output to standard output. A reader that went away early
/// (`| head`) is not an error.
pub fn emit(text: &str) -> Result<(), Failure> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(cable_dict::escape::terminal(text).as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::unsolved(
            anyhow::anyhow!("cannot write to standard output: {e}"),
        )),
        _ => Ok(()),
    }
}

/// Writes `spec` as a `.glb` file at `output`, atomically (`export-scene`, `sites --gltf`).
pub fn write_glb(
    output: &std::path::Path,
    spec: &cable_dict::report::scene::SceneSpec<'_>,
) -> Result<(), Failure> {
    let bytes = cable_dict::report::scene::to_glb(spec).map_err(Failure::unsolved)?;
    cable_dict::atomic_file::write_atomically(output, &bytes)
        .map_err(|e| Failure::input(anyhow::anyhow!("cannot write {}: {e}", output.display())))
}

pub use cable_dict::json::tidy;
