//! Where the impulses' labels go: beside their arrows, inside the plot,
//! never on top of another label or another arrow.
//!
//! Each label is tried at a few places around its arrow, nearest the tip
//! first (right of the tip, left of it, beyond it, a line or two further
//! towards the axis on either side, then behind the base, across the zero
//! line); the first place inside the plot that touches no
//! label placed before it and no other arrow wins. A label with no such
//! place is left out: the arrow still shows the impulse, its size is in
//! `ecam table show`. Pure pixel geometry, so a test can check it without
//! drawing.

/// A rectangle in pixels: `x`, `y` its top-left corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    /// Left edge.
    pub x: i32,
    /// Top edge.
    pub y: i32,
    /// Width.
    pub w: i32,
    /// Height.
    pub h: i32,
}

impl Rect {
    fn overlaps(&self, other: &Rect) -> bool {
        self.x < other.x + other.w
            && other.x < self.x + self.w
            && self.y < other.y + other.h
            && other.y < self.y + self.h
    }

    fn inside(&self, outer: &Rect) -> bool {
        self.x >= outer.x
            && self.y >= outer.y
            && self.x + self.w <= outer.x + outer.w
            && self.y + self.h <= outer.y + outer.h
    }
}

/// One arrow to label: its shaft from `base_y` to `tip_y` at `x`, and the
/// size of its label's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Arrow {
    /// Pixel column of the shaft.
    pub x: i32,
    /// Where the shaft starts (the zero line).
    pub base_y: i32,
    /// Where the head points.
    pub tip_y: i32,
    /// Text width in pixels.
    pub text_w: i32,
    /// Text height in pixels.
    pub text_h: i32,
}

/// Gap between an arrow and its label, pixels.
const GAP: i32 = 4;
/// Half the width of an arrow, head included, as an obstacle.
const ARROW_HALF: i32 = 5;

/// The top-left corner of each arrow's label inside `plot`, or `None`
/// where it has no room; no two placed labels overlap, none covers another
/// arrow, and all lie inside `plot`.
pub fn place(arrows: &[Arrow], plot: Rect) -> Vec<Option<(i32, i32)>> {
    let shafts: Vec<Rect> = arrows
        .iter()
        .map(|a| Rect {
            x: a.x - ARROW_HALF - GAP / 2,
            y: a.base_y.min(a.tip_y),
            w: 2 * ARROW_HALF + GAP,
            h: (a.base_y - a.tip_y).abs().max(1),
        })
        .collect();
    let mut placed: Vec<Rect> = Vec::with_capacity(arrows.len());
    arrows
        .iter()
        .enumerate()
        .map(|(k, a)| {
            // Towards the axis from the tip: down for an arrow pointing up.
            let inward = if a.tip_y <= a.base_y { 1 } else { -1 };
            let top_at = |row: i32| {
                if inward > 0 {
                    a.tip_y + row * (a.text_h + 2)
                } else {
                    a.tip_y - a.text_h - row * (a.text_h + 2)
                }
            };
            let right = a.x + ARROW_HALF + GAP;
            let left = a.x - ARROW_HALF - GAP - a.text_w;
            // Beyond the head, centred on the shaft (where a short arrow
            // leaves room), after the two sides of the tip.
            let beyond = [
                a.x - a.text_w / 2,
                a.x + ARROW_HALF - a.text_w,
                a.x - ARROW_HALF,
            ]
            .map(|x| Rect {
                x,
                y: top_at(-1) - inward * GAP,
                w: a.text_w,
                h: a.text_h,
            });
            let beside = |row: i32| {
                [right, left].map(|x| Rect {
                    x,
                    y: top_at(row),
                    w: a.text_w,
                    h: a.text_h,
                })
            };
            // Behind the base, on the other side of the zero line, where
            // arrows of the other sign are few.
            let behind_y = if inward > 0 {
                a.base_y + GAP
            } else {
                a.base_y - GAP - a.text_h
            };
            let behind = [a.x - a.text_w / 2, right, left].map(|x| Rect {
                x,
                y: behind_y,
                w: a.text_w,
                h: a.text_h,
            });
            let candidates = beside(0)
                .into_iter()
                .chain(beyond)
                .chain((1..3).flat_map(beside))
                .chain(behind);
            let mut fits = candidates.filter(|r| {
                r.inside(&plot)
                    && placed.iter().all(|p| !p.overlaps(r))
                    && shafts
                        .iter()
                        .enumerate()
                        .all(|(j, s)| j == k || !s.overlaps(r))
            });
            fits.next().map(|r| {
                placed.push(r);
                (r.x, r.y)
            })
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    const PLOT: Rect = Rect {
        x: 0,
        y: 0,
        w: 400,
        h: 200,
    };

    fn arrow(x: i32, up: bool) -> Arrow {
        Arrow {
            x,
            base_y: 100,
            tip_y: if up { 10 } else { 190 },
            text_w: 60,
            text_h: 12,
        }
    }

    fn boxes(arrows: &[Arrow]) -> Vec<Rect> {
        place(arrows, PLOT)
            .iter()
            .zip(arrows)
            .filter_map(|(p, a)| {
                p.map(|(x, y)| Rect {
                    x,
                    y,
                    w: a.text_w,
                    h: a.text_h,
                })
            })
            .collect()
    }

    #[test]
    fn labels_never_overlap_cover_arrows_or_leave_the_plot() {
        // Arrows 6 px apart, both ways and of many lengths, up to the
        // right edge.
        let arrows: Vec<Arrow> = (0..60)
            .map(|i| {
                let mut a = arrow(5 + 6 * i, i % 3 != 0);
                let len = 12 + (i * 37) % 78;
                a.tip_y = if a.tip_y < a.base_y {
                    100 - len
                } else {
                    100 + len
                };
                a
            })
            .collect();
        let placed = boxes(&arrows);
        assert!(!placed.is_empty());
        for (i, a) in placed.iter().enumerate() {
            assert!(a.inside(&PLOT), "{a:?}");
            for b in &placed[i + 1..] {
                assert!(!a.overlaps(b), "{a:?} {b:?}");
            }
            for arrow in &arrows {
                let shaft = Rect {
                    x: arrow.x - 1,
                    y: arrow.tip_y.min(arrow.base_y),
                    w: 2,
                    h: (arrow.tip_y - arrow.base_y).abs(),
                };
                let own = arrow.x + ARROW_HALF + GAP == a.x
                    || arrow.x - ARROW_HALF - GAP - arrow.text_w == a.x;
                assert!(
                    own || !a.overlaps(&shaft),
                    "{a:?} over the arrow at {}",
                    arrow.x
                );
            }
        }
    }

    #[test]
    fn a_label_at_the_right_edge_goes_left_of_its_arrow() {
        let placed = place(&[arrow(398, true)], PLOT);
        let (x, _) = placed[0].unwrap();
        assert!(x + 60 <= 400 && x < 398);
    }

    #[test]
    fn labels_far_apart_are_all_placed() {
        let arrows = [arrow(50, true), arrow(200, false), arrow(350, true)];
        assert!(place(&arrows, PLOT).iter().all(Option::is_some));
    }
}
