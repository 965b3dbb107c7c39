//! The report's plot: milliseconds per step and per frame against the particle
//! count, log–log, one line per backend and job, written as a PNG with plotters
//! (its bitmap backend; labels in a TrueType font found on the system, because
//! plotters' own font loading needs fontconfig and freetype headers to build).

use std::path::Path;

use plotters::prelude::*;

/// One line of the plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Its legend, e.g. "vk frame".
    pub label: String,
    /// `(particles, milliseconds)`, in increasing particles.
    pub points: Vec<(f64, f64)>,
}

/// Why the plot was not written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// No font to label the axes with.
    #[error(
        "no TrueType font found (looked in {0}): install one, e.g. `apt-get install fonts-dejavu-core`"
    )]
    NoFont(String),
    /// Nothing to plot.
    #[error("no measurements to plot")]
    Empty,
    /// plotters failed.
    #[error("drawing the plot: {0}")]
    Drawing(String),
}

/// Where fonts usually are.
const FONT_PATHS: [&str; 6] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/Library/Fonts/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

fn register_font() -> Result<(), PlotError> {
    for path in FONT_PATHS {
        if let Ok(bytes) = std::fs::read(path) {
            // plotters keeps fonts for the process's life.
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            if plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                return Ok(());
            }
        }
    }
    Err(PlotError::NoFont(FONT_PATHS.join(", ")))
}

fn drawing<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError::Drawing(format!("{e:?}"))
}

/// Writes `series` as a log–log PNG of 1000×640 px to `path`.
pub fn write_png(path: &Path, title: &str, series: &[Series]) -> Result<(), PlotError> {
    let points = || series.iter().flat_map(|s| s.points.iter().copied());
    let (Some(x_min), Some(x_max)) = (
        points().map(|p| p.0).reduce(f64::min),
        points().map(|p| p.0).reduce(f64::max),
    ) else {
        return Err(PlotError::Empty);
    };
    let y_min = points()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .max(1e-3);
    let y_max = points().map(|p| p.1).fold(0.0, f64::max).max(y_min * 10.0);
    register_font()?;
    let root = BitMapBackend::new(path, (1000, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(drawing)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 24))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(
            (x_min * 0.8..x_max * 1.25).log_scale(),
            (y_min * 0.5..y_max * 2.0).log_scale(),
        )
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc("particles")
        .y_desc("milliseconds")
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y}"))
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(drawing)?;
    for (i, s) in series.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        let style = ShapeStyle::from(colour).stroke_width(2);
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), style))
            .map_err(drawing)?
            .label(s.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        chart
            .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(drawing)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()
        .map_err(drawing)?;
    root.present().map_err(drawing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_or_says_which_font_is_missing() {
        let path = std::env::temp_dir().join(format!("precip-plot-{}.png", std::process::id()));
        let series = [Series {
            label: "cpu step".into(),
            points: vec![(1e4, 2.0), (1e5, 14.0), (1e6, 141.0)],
        }];
        match write_png(&path, "test", &series) {
            Ok(()) => {
                let bytes = std::fs::read(&path).expect("written");
                assert_eq!(&bytes[1..4], b"PNG");
                let _ = std::fs::remove_file(&path);
            }
            Err(PlotError::NoFont(paths)) => eprintln!("no font here ({paths})"),
            Err(e) => panic!("{e}"),
        }
        assert!(matches!(
            write_png(&path, "empty", &[]),
            Err(PlotError::Empty)
        ));
    }
}
