//! The step parameters a learner can learn, and sets of them.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// One learnable step parameter.
///
/// The Capture Step controller decides three things about the next step: where it lands
/// sagittally (`F`), laterally (`W`), and when (`T`). A learner adds an offset to any set of
/// them: [`StepParameter::StepX`] is the paper's dF, [`StepParameter::StepY`] the lateral dW,
/// [`StepParameter::StepTime`] a step-time offset dT. Beside the step, the body itself:
/// [`StepParameter::AnklePitch`] and [`StepParameter::AnkleRoll`] turn the support sole (an
/// ankle strategy, learned, in each plane).
/// [`PerParameter`] holds one value per
/// parameter (inputs, outcomes, reaches, offsets); [`LearnSet`] says which ones a learner learns;
/// [`Plane`] is the plane whose state and outcome a parameter's learner reads, [`Planes`] the
/// planes a parameter is learned in (the step time may be learned in both at once).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    Serialize,
    Deserialize,
    strum::EnumString,
    strum::Display,
    strum::IntoStaticStr,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum StepParameter {
    /// The sagittal footstep offset dF (m, forward positive): the paper's (the default).
    #[default]
    StepX,
    /// The lateral step-width offset dW (m, towards the swing leg's side).
    StepY,
    /// The step-time offset dT (s, later positive).
    StepTime,
    /// The support sole's pitch offset dA (rad, toe down positive): a learned ankle strategy.
    /// The position-controlled ankle presses the toe (positive) or the heel (negative) into
    /// the ground, moving the centre of pressure under the support foot while the catch step
    /// is still in the air.
    AnklePitch,
    /// The support sole's roll offset dR (rad, positive presses the sole's edge on the swing
    /// leg's side): the frontal-plane ankle strategy, learned. It moves the centre of pressure
    /// under the support foot sideways, towards the swing leg's side when positive.
    AnkleRoll,
}

impl StepParameter {
    /// How many parameters there are.
    pub const COUNT: usize = 5;

    /// Every parameter, in their fixed order.
    pub const ALL: [StepParameter; Self::COUNT] = [
        Self::StepX,
        Self::StepY,
        Self::StepTime,
        Self::AnklePitch,
        Self::AnkleRoll,
    ];

    /// Whether this is the paper's `step-x`.
    pub fn is_step_x(&self) -> bool {
        *self == StepParameter::StepX
    }

    /// Whether this parameter's offset, and so its step error F_E, is a length in metres
    /// (`step-x`, `step-y`); the step time's is in seconds and the soles' in radians.
    pub fn is_length(self) -> bool {
        matches!(self, StepParameter::StepX | StepParameter::StepY)
    }

    /// Position in [`Self::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The name on the command line and in config files (`step-x`, `step-y`, `step-time`,
    /// `ankle-pitch`, `ankle-roll`).
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// The plane this parameter is learned in unless its settings name another: `step-x`,
    /// `step-time` and `ankle-pitch` the sagittal, `step-y` and `ankle-roll` the frontal.
    pub fn default_plane(self) -> Plane {
        match self {
            StepParameter::StepX | StepParameter::StepTime | StepParameter::AnklePitch => {
                Plane::Sagittal
            }
            StepParameter::StepY | StepParameter::AnkleRoll => Plane::Frontal,
        }
    }

    /// Whether this parameter may be learned in `planes`: a footstep offset and the sole's
    /// pitch or roll only in their own plane, the step time (which moves the capture point in both) in either or both.
    pub fn allows(self, planes: Planes) -> bool {
        self == StepParameter::StepTime || planes == Planes::from(self.default_plane())
    }
}

/// The plane whose state (theta_E, its rate, the reference) a learner reads and whose
/// touch-down outcome teaches it: the sagittal plane of the paper, or the frontal plane
/// mirrored to the swing leg's side (the lateral learner's, docs/lateral.md).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    Serialize,
    Deserialize,
    strum::EnumString,
    strum::Display,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum Plane {
    /// Forward and backward.
    #[default]
    Sagittal,
    /// Sideways, mirrored to the swing leg's side.
    Frontal,
}

/// The planes a parameter is learned in (its table's `plane` key): one, or both at once. In
/// both, the parameter's offset is the sum of one learner per plane, each reading its plane's
/// state and taught by its plane's outcome
/// ([`StepLearner`](super::step_learner::StepLearner)).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, strum::EnumString, strum::Display,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum Planes {
    /// The sagittal plane alone.
    Sagittal,
    /// The frontal plane alone.
    Frontal,
    /// Both, one learner each, their offsets summed.
    Both,
}

impl Planes {
    /// The one plane, unless both.
    pub fn single(self) -> Option<Plane> {
        match self {
            Planes::Sagittal => Some(Plane::Sagittal),
            Planes::Frontal => Some(Plane::Frontal),
            Planes::Both => None,
        }
    }

    /// Each plane, sagittal first.
    pub fn iter(self) -> impl Iterator<Item = Plane> {
        const BOTH: [Plane; 2] = [Plane::Sagittal, Plane::Frontal];
        let planes: &'static [Plane] = match self {
            Planes::Sagittal => &BOTH[..1],
            Planes::Frontal => &BOTH[1..],
            Planes::Both => &BOTH,
        };
        planes.iter().copied()
    }
}

impl From<Plane> for Planes {
    fn from(plane: Plane) -> Self {
        match plane {
            Plane::Sagittal => Planes::Sagittal,
            Plane::Frontal => Planes::Frontal,
        }
    }
}

/// What a learned offset is weighted by each tick (its table's `gate` key).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Gate {
    /// The offset acts whole (the default). A parameter learned in both planes is the sum of
    /// its parts.
    #[default]
    Off,
    /// The offset of a learner reading `plane` is weighted by that plane's share of the trunk's
    /// squared deviation rate, `r_plane^2 / (r_sagittal^2 + r_frontal^2)` (half when both are
    /// 0): it acts when the trunk falls in its plane and fades when it falls in the other.
    RateShare,
    /// The offset acts only while it points the way the trunk falls in its plane (its sign that
    /// of the plane's deviation rate) and is withheld while it points against the fall: a
    /// pressed heel, or a shorter step, while the trunk falls forward. For offsets with a
    /// direction in space (`step-x`, `step-y`, `ankle-pitch`, `ankle-roll`), not the step time.
    /// A learner reads the rate's sign with hysteresis ([`FallDirection`]).
    WithTheFall,
}

impl Gate {
    /// The weight of `offset`, the output of a learner reading `plane`, at the planes'
    /// deviation rates, from this tick's rates alone (no hysteresis, see [`Self::weight_held`]).
    pub fn weight(self, plane: Plane, sagittal_rate: f64, frontal_rate: f64, offset: f64) -> f64 {
        let own_rate = own_rate(plane, sagittal_rate, frontal_rate);
        self.weight_falling(sagittal_rate, frontal_rate, own_rate, offset, own_rate)
    }

    /// [`Self::weight`] with hysteresis on the fall direction: `fall`, the direction this
    /// plane's learner last saw, is updated from the plane's rate first and
    /// [`Gate::WithTheFall`] reads it instead of the rate's raw sign, so a rate dithering
    /// within [`FALL_DIRECTION_BAND`] of 0 does not toggle the offset on and off. The other
    /// gates do not read `fall`.
    pub fn weight_held(
        self,
        plane: Plane,
        sagittal_rate: f64,
        frontal_rate: f64,
        offset: f64,
        fall: &mut FallDirection,
    ) -> f64 {
        let own_rate = own_rate(plane, sagittal_rate, frontal_rate);
        let falling = fall.update(own_rate);
        self.weight_falling(sagittal_rate, frontal_rate, own_rate, offset, falling)
    }

    /// The weight with the plane's own rate `own_rate` and `falling`, a value whose sign is
    /// the direction [`Gate::WithTheFall`] reads (0: none).
    fn weight_falling(
        self,
        sagittal_rate: f64,
        frontal_rate: f64,
        own_rate: f64,
        offset: f64,
        falling: f64,
    ) -> f64 {
        match self {
            Gate::Off => 1.0,
            Gate::RateShare => {
                let (s, f) = (sagittal_rate * sagittal_rate, frontal_rate * frontal_rate);
                if s + f > 0.0 {
                    own_rate * own_rate / (s + f)
                } else {
                    0.5
                }
            }
            Gate::WithTheFall => {
                if offset * falling > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// Whether this gate may weight `parameter`'s offset ([`Gate::WithTheFall`] needs an
    /// offset with a direction in space, so not the step time's).
    pub fn allows(self, parameter: StepParameter) -> bool {
        self != Gate::WithTheFall || parameter != StepParameter::StepTime
    }
}

/// The deviation rate of `plane` of the two planes' rates.
fn own_rate(plane: Plane, sagittal_rate: f64, frontal_rate: f64) -> f64 {
    match plane {
        Plane::Sagittal => sagittal_rate,
        Plane::Frontal => frontal_rate,
    }
}

/// The half-width of the band of deviation rates around 0 (rad/s) within which
/// [`FallDirection`] keeps the direction it last saw. Small beside the rates a push or a
/// stumble gives the trunk, large beside the tick-to-tick jitter of the rate of a trunk
/// standing nearly still, which without it would switch a [`Gate::WithTheFall`] offset on
/// and off from one tick to the next.
pub const FALL_DIRECTION_BAND: f64 = 0.05;

/// The direction the trunk falls in one plane, with hysteresis: the sign of the plane's
/// deviation rate once the rate leaves +-[`FALL_DIRECTION_BAND`], kept while it is inside.
/// None (0) until the rate first leaves the band. Not part of a checkpoint: a restored
/// learner's direction starts at none.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FallDirection(f64);

impl FallDirection {
    /// The direction after a tick at `rate`: +1, -1, or 0 before any rate left the band.
    pub fn update(&mut self, rate: f64) -> f64 {
        if rate.abs() > FALL_DIRECTION_BAND {
            self.0 = rate.signum();
        }
        self.0
    }

    /// The direction last seen (+1, -1, or 0 for none).
    pub fn get(self) -> f64 {
        self.0
    }
}

/// One value per step parameter, indexed by [`StepParameter`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PerParameter<T>(pub [T; StepParameter::COUNT]);

impl<T: Copy> PerParameter<T> {
    /// `value` for every parameter.
    pub fn splat(value: T) -> Self {
        PerParameter([value; StepParameter::COUNT])
    }

    /// Each parameter's value from its default plane's ([`StepParameter::default_plane`]):
    /// `sagittal` for `step-x`, `step-time` and `ankle-pitch`, `frontal` for `step-y` and
    /// `ankle-roll` (the walker's inputs and outcomes).
    pub fn from_planes(sagittal: T, frontal: T) -> Self {
        PerParameter(StepParameter::ALL.map(|p| match p.default_plane() {
            Plane::Sagittal => sagittal,
            Plane::Frontal => frontal,
        }))
    }
}

impl<T: Default> PerParameter<T> {
    /// `value` for `p`, the default (0, `None`) for every other parameter: a policy's offsets
    /// or reports for the one parameter it learns.
    pub fn only(p: StepParameter, value: T) -> Self {
        let mut out = PerParameter::default();
        out[p] = value;
        out
    }
}

impl<T> PerParameter<T> {
    /// The value of `p`.
    pub fn get(&self, p: StepParameter) -> &T {
        &self.0[p.index()]
    }

    /// The value of `p`, mutably.
    pub fn get_mut(&mut self, p: StepParameter) -> &mut T {
        &mut self.0[p.index()]
    }

    /// Each value transformed.
    pub fn map<U>(self, f: impl FnMut(T) -> U) -> PerParameter<U> {
        PerParameter(self.0.map(f))
    }

    /// `p`'s value read in `plane`: its own in its default plane
    /// ([`StepParameter::default_plane`]), else the value of the footstep offset learned in
    /// `plane` (the walker's inputs and outcomes hold the sagittal plane at `step-x`, the
    /// frontal at `step-y`).
    pub fn in_plane(&self, p: StepParameter, plane: Plane) -> &T {
        match plane {
            _ if plane == p.default_plane() => &self[p],
            Plane::Sagittal => &self[StepParameter::StepX],
            Plane::Frontal => &self[StepParameter::StepY],
        }
    }
}

impl<T> std::ops::Index<StepParameter> for PerParameter<T> {
    type Output = T;
    fn index(&self, p: StepParameter) -> &T {
        self.get(p)
    }
}

impl<T> std::ops::IndexMut<StepParameter> for PerParameter<T> {
    fn index_mut(&mut self, p: StepParameter) -> &mut T {
        self.get_mut(p)
    }
}

/// A malformed set of step parameters.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum LearnSetError {
    /// A name that is not a step parameter.
    #[error(
        "unknown step parameter {0:?} (expected step-x, step-y, step-time, ankle-pitch or ankle-roll)"
    )]
    Unknown(String),
    /// A parameter named twice.
    #[error("step parameter {0} named twice")]
    Repeated(StepParameter),
    /// No parameter at all.
    #[error(
        "the set of learned step parameters is empty (expected one or more of step-x, step-y, step-time, ankle-pitch, ankle-roll)"
    )]
    Empty,
}

/// A non-empty set of step parameters that a learner learns. Written as a list of names
/// (`["step-x", "step-time"]` in config files, `step-x,step-time` on the command line), always
/// in the order of [`StepParameter::ALL`]. The default is the paper's `step-x`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "Vec<String>", into = "Vec<String>")]
pub struct LearnSet([bool; StepParameter::COUNT]);

impl Default for LearnSet {
    fn default() -> Self {
        LearnSet::of(&[StepParameter::StepX]).expect("non-empty")
    }
}

impl LearnSet {
    /// The set of `parameters` (each at most once, at least one).
    pub fn of(parameters: &[StepParameter]) -> Result<Self, LearnSetError> {
        let mut set = [false; StepParameter::COUNT];
        for &p in parameters {
            if std::mem::replace(&mut set[p.index()], true) {
                return Err(LearnSetError::Repeated(p));
            }
        }
        if set.iter().any(|&b| b) {
            Ok(LearnSet(set))
        } else {
            Err(LearnSetError::Empty)
        }
    }

    /// Whether `p` is in the set.
    pub fn contains(&self, p: StepParameter) -> bool {
        self.0[p.index()]
    }

    /// The parameters in the set, in the order of [`StepParameter::ALL`].
    pub fn iter(&self) -> impl Iterator<Item = StepParameter> + '_ {
        StepParameter::ALL.into_iter().filter(|p| self.contains(*p))
    }

    /// The names, in order.
    pub fn names(&self) -> Vec<&'static str> {
        self.iter().map(StepParameter::name).collect()
    }

    /// Whether this is the paper's set, `step-x` alone.
    pub fn is_paper(&self) -> bool {
        *self == LearnSet::default()
    }
}

impl FromStr for LearnSet {
    type Err = LearnSetError;
    /// Comma-separated names: `step-x,step-time`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let names: Vec<String> = s.split(',').map(|n| n.trim().to_string()).collect();
        LearnSet::try_from(names)
    }
}

impl TryFrom<Vec<String>> for LearnSet {
    type Error = LearnSetError;
    fn try_from(names: Vec<String>) -> Result<Self, Self::Error> {
        let parameters = names
            .iter()
            .map(|n| StepParameter::from_str(n).map_err(|_| LearnSetError::Unknown(n.clone())))
            .collect::<Result<Vec<_>, _>>()?;
        LearnSet::of(&parameters)
    }
}

impl From<LearnSet> for Vec<String> {
    fn from(set: LearnSet) -> Self {
        set.iter().map(|p| p.name().to_string()).collect()
    }
}

impl fmt::Display for LearnSet {
    /// Comma-separated names, as on the command line.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.names().join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_parse_in_any_order_and_print_in_the_fixed_one() {
        let s: LearnSet = "step-time, step-x".parse().unwrap();
        assert_eq!(s.to_string(), "step-x,step-time");
        assert!(s.contains(StepParameter::StepTime) && !s.contains(StepParameter::StepY));
        assert_eq!(LearnSet::default().to_string(), "step-x");
        assert!(LearnSet::default().is_paper() && !s.is_paper());
        let all: LearnSet = "ankle-roll,ankle-pitch,step-time,step-y,step-x"
            .parse()
            .unwrap();
        assert_eq!(
            all.to_string(),
            "step-x,step-y,step-time,ankle-pitch,ankle-roll"
        );
        assert!(StepParameter::AnklePitch.allows(Planes::Sagittal));
        assert!(!StepParameter::AnklePitch.allows(Planes::Both));
        assert!(StepParameter::AnkleRoll.allows(Planes::Frontal));
        assert!(!StepParameter::AnkleRoll.allows(Planes::Sagittal));
        assert!(!StepParameter::AnkleRoll.allows(Planes::Both));
    }

    #[test]
    fn per_parameter_values_come_from_their_default_planes() {
        let v = PerParameter::from_planes(1, 2);
        assert_eq!(v.0, [1, 2, 1, 1, 2]);
        for p in StepParameter::ALL {
            let want = if p.default_plane() == Plane::Sagittal {
                1
            } else {
                2
            };
            assert_eq!(v[p], want);
            assert_eq!(*v.in_plane(p, p.default_plane()), want);
        }
        assert_eq!(PerParameter::splat(7).0, [7; StepParameter::COUNT]);
        let one = PerParameter::only(StepParameter::StepTime, Some(3));
        assert_eq!(one.0, [None, None, Some(3), None, None]);
    }

    #[test]
    fn bad_sets_are_refused_with_the_reason() {
        assert_eq!(
            "step-x,step-z".parse::<LearnSet>(),
            Err(LearnSetError::Unknown("step-z".into()))
        );
        assert_eq!(
            "step-x,step-x".parse::<LearnSet>(),
            Err(LearnSetError::Repeated(StepParameter::StepX))
        );
        assert_eq!(LearnSet::of(&[]), Err(LearnSetError::Empty));
        assert!("".parse::<LearnSet>().is_err());
    }

    #[test]
    fn only_the_step_time_is_learned_in_both_planes() {
        let both: Vec<Plane> = Planes::Both.iter().collect();
        assert_eq!(both, [Plane::Sagittal, Plane::Frontal]);
        assert_eq!(Planes::Frontal.iter().collect::<Vec<_>>(), [Plane::Frontal]);
        assert_eq!(Planes::Both.single(), None);
        assert_eq!(Planes::Sagittal.single(), Some(Plane::Sagittal));
        assert!(StepParameter::StepTime.allows(Planes::Both));
        assert!(!StepParameter::StepX.allows(Planes::Both));
        assert!(!StepParameter::StepY.allows(Planes::Sagittal));
        assert!(StepParameter::StepY.allows(Planes::Frontal));
        assert_eq!("both".parse::<Planes>(), Ok(Planes::Both));
    }

    #[test]
    fn with_the_fall_holds_its_state_while_the_rate_dithers_within_the_band() {
        let gate = Gate::WithTheFall;
        let mut fall = FallDirection::default();
        let w = |fall: &mut FallDirection, rate: f64| {
            gate.weight_held(Plane::Sagittal, rate, 0.0, 0.1, fall)
        };
        // Closed until the rate first leaves the band, however its sign dithers.
        let dither = [0.4, -0.6, 0.9, -0.2].map(|k| k * FALL_DIRECTION_BAND);
        for r in dither {
            assert_eq!(w(&mut fall, r), 0.0);
        }
        // Falling forward beyond the band: open, and it stays open while the rate dithers
        // around 0 inside the band (the stateless weight would toggle).
        assert_eq!(w(&mut fall, 1.5 * FALL_DIRECTION_BAND), 1.0);
        let mut toggles = 0;
        for r in dither {
            assert_eq!(w(&mut fall, r), 1.0);
            toggles += usize::from(gate.weight(Plane::Sagittal, r, 0.0, 0.1) == 0.0);
        }
        assert_eq!(toggles, 2);
        // Beyond the band the other way: closed.
        assert_eq!(w(&mut fall, -1.5 * FALL_DIRECTION_BAND), 0.0);
        assert_eq!(fall.get(), -1.0);
        assert_eq!(w(&mut fall, 0.9 * FALL_DIRECTION_BAND), 0.0);
        // The other plane's rate does not move this plane's direction.
        let mut frontal = FallDirection::default();
        assert_eq!(
            gate.weight_held(Plane::Frontal, 1.0, 0.2, 0.1, &mut frontal),
            1.0
        );
        assert_eq!(
            gate.weight_held(Plane::Frontal, -1.0, 0.0, 0.1, &mut frontal),
            1.0
        );
        // The other gates ignore the held direction.
        assert_eq!(
            Gate::Off.weight_held(Plane::Sagittal, -1.0, 0.0, 0.1, &mut fall),
            1.0
        );
    }

    #[test]
    fn sets_round_trip_through_toml_as_lists_of_names() {
        #[derive(Serialize, Deserialize)]
        struct T {
            learn: LearnSet,
        }
        let t: T = toml::from_str("learn = [\"step-y\", \"step-x\"]").unwrap();
        assert_eq!(t.learn.to_string(), "step-x,step-y");
        let text = toml::to_string(&t).unwrap();
        assert_eq!(text.trim(), "learn = [\"step-x\", \"step-y\"]");
        assert!(toml::from_str::<T>("learn = []").is_err());
        assert!(toml::from_str::<T>("learn = [\"dT\"]").is_err());
    }
}
