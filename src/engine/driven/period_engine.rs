//! The driven engine as a [`PeriodEngine`]: what the analysis asks of it.

use super::super::{Event, Observer, PeriodEnd, PeriodEngine, PeriodStart, Segment, WorkCounters};
use super::{DriveProfile, DrivenEngine, DrivenState, SpringProfile, profile, spring_profile};
use crate::error::SimulationError;
use crate::signal::Signal;

impl PeriodEngine for DrivenEngine<'_> {
    fn signal(&self) -> &Signal {
        self.signal
    }

    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        self.run_period_impl(period, start, observer)
    }

    fn counters(&self) -> WorkCounters {
        self.counters
    }

    fn zero_velocity_tolerance(&self) -> f64 {
        self.contact.tol_v
    }

    fn last_velocity_uncertainty(&self) -> Option<f64> {
        Some(self.last_uncertainty)
    }

    /// The largest event-time bound of the last period: the solver's
    /// tolerance plus `eta / |v_rel'|` at each zero of `v_rel`.
    fn event_time_uncertainty(&self) -> f64 {
        self.last_time_error
    }

    fn carries_rod_state(&self) -> bool {
        true
    }

    fn drive_profile(&self, segments: &[Segment]) -> Option<DriveProfile> {
        let Signal::Fourier(signal) = self.signal else {
            return None;
        };
        let rod = self.rod?;
        profile::profile(segments, rod, signal, |segment| {
            self.segment_functions(segment, None)
        })
    }

    fn boundary_state(&self) -> Option<DrivenState> {
        self.state
    }

    fn spring_profile(
        &self,
        start: &DrivenState,
        (segments, events): (&[Segment], &[Event]),
        periods: u64,
    ) -> Option<SpringProfile> {
        let law = self.spring.as_ref()?;
        Some(spring_profile::profile(
            law,
            start,
            (segments, events),
            (self.period, periods),
            |dir| self.contact.slip_acceleration(dir),
            |segment, contact| self.segment_functions(segment, Some(contact)),
        ))
    }

    fn restart_from(&mut self, state: DrivenState) -> bool {
        self.state = Some(state);
        true
    }
}
