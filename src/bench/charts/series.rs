//! Chart data: named series of points, each point optionally with an interval
//! (drawn as an error bar).

/// One point; `interval` is the (low, high) range of its y value, e.g. a
/// confidence interval or the spread of repeats.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    pub interval: Option<(f64, f64)>,
}

impl Point {
    pub fn new(x: f64, y: f64) -> Self {
        Point { x, y, interval: None }
    }

    pub fn with_interval(mut self, low: f64, high: f64) -> Self {
        self.interval = Some((low, high));
        self
    }

    /// Whether the interval holds 0: the value is within noise of nothing
    /// (drawn as a hollow marker).
    pub fn interval_holds_zero(&self) -> bool {
        self.interval.is_some_and(|(low, high)| low <= 0.0 && 0.0 <= high)
    }
}

impl From<(f64, f64)> for Point {
    fn from((x, y): (f64, f64)) -> Self {
        Point::new(x, y)
    }
}

/// One named set of points, e.g. all runs of one strategy.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<Point>,
    /// `None` takes the next palette colour.
    pub color: Option<[u8; 3]>,
}

impl Series {
    /// From (x, y) pairs, without intervals.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series::with_points(name, points.into_iter().map(Point::from).collect())
    }

    /// From points that may carry intervals (error bars).
    pub fn with_points(name: impl Into<String>, points: Vec<Point>) -> Self {
        Series { name: name.into(), points, color: None }
    }

    pub fn with_color(mut self, color: [u8; 3]) -> Self {
        self.color = Some(color);
        self
    }
}

/// One bar of a stacked bar chart: its label (a category on the x axis) and its
/// segments, bottom up, as (segment name, value). Segment names are shared
/// across bars (one legend entry and colour each, in order of first appearance).
#[derive(Debug, Clone, PartialEq)]
pub struct StackedBar {
    pub label: String,
    pub segments: Vec<(String, f64)>,
}

/// One named set of values whose distribution a histogram shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution {
    pub name: String,
    pub values: Vec<f64>,
}

impl Distribution {
    pub fn new(name: impl Into<String>, values: Vec<f64>) -> Self {
        Distribution { name: name.into(), values }
    }
}
