//! The `[spring]` table of a scene file as written, and the spring it
//! gives (docs/interface.md; docs/model.md section 17), and what a spring
//! asks of the rest of the scene.

use super::{EngineKind, Scene};
use crate::error::{Num, ParamError};
use crate::signal::SignalSpec;
use crate::spring::{Spring, SpringEnd};
use serde::{Deserialize, Serialize};

/// The `[spring]` table: a spring against the slider.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringTable {
    /// `k`, N/m.
    pub stiffness: f64,
    /// `b`, N s/m (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// `true` (default): tied to the slider; `false`: a free end, pushing
    /// only while compressed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tied: Option<bool>,
    /// Free end: its distance ahead of the slider's start (m, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap: Option<f64>,
    /// Tied: the spring's force at the slider's start (N, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<f64>,
}

/// The spring of a `[spring]` table, checked ([`Spring::validate`]); a
/// field of the other kind of spring (`gap` on a tied one, `preload` on a
/// free end) is refused, naming it.
pub(super) fn spring_of(table: Option<SpringTable>) -> Result<Option<Spring>, ParamError> {
    let Some(t) = table else {
        return Ok(None);
    };
    let tied = t.tied.unwrap_or(true);
    let end = match (tied, t.gap, t.preload) {
        (true, Some(gap), _) => {
            return Err(ParamError::out_of_range(
                "spring.gap",
                gap,
                "applies to a free end (spring.tied = false); a tied spring takes spring.preload",
            ));
        }
        (false, _, Some(preload)) => {
            return Err(ParamError::out_of_range(
                "spring.preload",
                preload,
                format!(
                    "applies to a tied spring (spring.tied = true); a free end takes spring.gap \
                     (stiffness {})",
                    Num(t.stiffness)
                ),
            ));
        }
        (true, None, preload) => SpringEnd::Tied {
            preload: preload.unwrap_or(0.0),
        },
        (false, gap, None) => SpringEnd::Free {
            gap: gap.unwrap_or(0.0),
        },
    };
    let spring = Spring {
        stiffness: t.stiffness,
        damping: t.damping.unwrap_or(0.0),
        end,
    };
    spring.validate()?;
    Ok(Some(spring))
}

/// The `[spring]` table of a spring.
pub(super) fn spring_table(spring: Option<&Spring>) -> Option<SpringTable> {
    let s = spring?;
    let (tied, gap, preload) = match s.end {
        SpringEnd::Tied { preload } => (true, None, Some(preload)),
        SpringEnd::Free { gap } => (false, Some(gap), None),
    };
    Some(SpringTable {
        stiffness: s.stiffness,
        damping: Some(s.damping),
        tied: Some(tied),
        gap,
        preload,
    })
}

impl Scene {
    /// A spring needs a continuous signal (the exact engine's closed forms
    /// of a rod that follows a Fourier series, or of a driven rod) and the
    /// exact engine (`stickslip check` runs the fixed-step reference
    /// against it); its fields are checked by [`Spring::validate`].
    pub(super) fn check_spring(&self) -> Result<(), ParamError> {
        let Some(spring) = &self.spring else {
            return Ok(());
        };
        spring.validate()?;
        if matches!(self.signal, SignalSpec::Ideal(_)) {
            return Err(ParamError::Inconsistent {
                field: "spring".to_owned(),
                reason: "needs a continuous signal (signal.kind = \"fourier\" or \"harmonics\"): \
                         the ideal signal's jumps would strike the spring"
                    .to_owned(),
            });
        }
        if self.run.engine == EngineKind::Fixed {
            return Err(ParamError::Inconsistent {
                field: "run.engine".to_owned(),
                reason: "\"fixed\" has no steady orbit of its own against a spring (in slip-slip \
                         its period map is neutral, model section 12); run the exact engine, and \
                         compare the fixed-step reference with `stickslip check`"
                    .to_owned(),
            });
        }
        Ok(())
    }
}
