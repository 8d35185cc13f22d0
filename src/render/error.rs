//! Rendering errors.

use multibody_core::solve::SolutionError;

/// What can go wrong when rendering.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The image would have no pixels, or is too large (for a GIF, or for memory).
    #[error(
        "cannot render a {width}x{height} image: width and height must be 1 to 65535, \
         width * height at most 2^26"
    )]
    ImageSize {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// There are no frame times.
    #[error("no frame times to render")]
    NoFrames,
    /// A frame time is outside the solution's interval (or not a number).
    #[error("frame time t = {t} is outside the solved interval [{t0}, {t1}]")]
    TimeOutOfRange {
        /// The frame time.
        t: f64,
        /// First time of the solution.
        t0: f64,
        /// Last time of the solution.
        t1: f64,
    },
    /// The camera cannot be built from the options.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// A variable a part is placed by is not in the solution (the solution is not of
    /// this model).
    #[error("cannot draw `{component}`: {source}")]
    MissingVariable {
        /// The component's path.
        component: String,
        /// What the solution said.
        source: SolutionError,
    },
    /// Writing or encoding the image failed.
    #[error("cannot write `{path}`: {message}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
}

/// Rendering errors as the crate's [`Error`](crate::Error): a missing variable or a
/// time outside the solution as [`Error::Solution`](crate::Error::Solution), a failed
/// write as a plot I/O error, bad options as a plot backend error.
impl From<RenderError> for crate::Error {
    fn from(e: RenderError) -> Self {
        use multibody_core::plot::PlotError;
        match e {
            RenderError::MissingVariable { source, .. } => source.into(),
            RenderError::TimeOutOfRange { t, t0, t1 } => {
                SolutionError::OutOfRange { t, t0, t1 }.into()
            }
            RenderError::Write { .. } => PlotError::Io(e.to_string()).into(),
            _ => PlotError::Backend(e.to_string()).into(),
        }
    }
}
