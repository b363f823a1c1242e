//! The continuous genome's development: through its text, exactly as `ontogeny grow` develops
//! the printed file, building only the last frame.

use super::*;
use crate::develop::Seedling;

impl ContinuousGenome {
    /// The grammar the genome's text compiles to, with the options that develop it in its own
    /// environment or in `env` (of the same size: its initial values replace the genome's).
    pub(super) fn seedling_in(
        &self,
        limits: &ContinuousLimits,
        env: Option<&Environment>,
    ) -> Result<Seedling, DevelopError> {
        let limits = limits.sane();
        // A genome from elsewhere (a store, a hand-edited file) may not fit: its time and
        // frames would be unbounded.
        self.check_limits(&limits)
            .map_err(|e| DevelopError(format!("the genome exceeds its limits: {e}")))?;
        let lsys = LSystem::from_text(Self::NAME, &self.to_text())
            .map_err(|d| DevelopError(d.to_string()))?;
        Ok(Seedling {
            lsys: std::sync::Arc::new(lsys),
            derive: DeriveOptions {
                max_modules: limits.max_modules,
                env: env
                    .map(|e| e.values().iter().copied().enumerate().collect())
                    .unwrap_or_default(),
                ..DeriveOptions::default()
            },
            build: BuildOptions {
                max_parts: limits.max_parts,
                ..BuildOptions::default()
            },
        })
    }

    /// The creature the genome grows into at the end of its developmental time, in its own
    /// environment or in `env` (of the same size: its initial values replace the genome's).
    pub(super) fn creature(
        &self,
        limits: &ContinuousLimits,
        env: Option<&Environment>,
    ) -> Result<Creature, DevelopError> {
        let Seedling {
            lsys,
            derive: options,
            build: build_options,
        } = self.seedling_in(limits, env)?;
        // What `develop::grow` does, building only the last frame.
        let mut last = None;
        lsys.for_each_frame(&options, None, |frame| {
            if frame.last {
                last = Some(crate::develop::build_frame(
                    &lsys,
                    &frame,
                    &options,
                    &build_options,
                )?);
            }
            Ok::<(), crate::lang::Diagnostic>(())
        })
        .map_err(|d| DevelopError(d.to_string()))?;
        let creature =
            last.ok_or_else(|| DevelopError("development showed no last frame".into()))?;
        Ok(Creature {
            projectile: self.projectile,
            ..creature
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn growth_doubles_once_per_min_duration_and_no_more() {
        // Two limbs that each branch into two every time unit (threshold 0.2, rate 0.2), over
        // 4 time units: generations born at t = 0, 1, 2, 3, 4 hold 2, 4, 8, 16, 32 tokens;
        // the first four matured into 30 parts, the last is just born.
        let mf = Grower::Maturing(Command::Forward);
        let g = ContinuousGenome::on_a_forward_part(
            4.0,
            &[mf, mf],
            vec![Rule {
                grower: mf,
                threshold: 0.2,
                rate: 0.2,
                successor: vec![
                    Token::Push,
                    Token::Command(Command::Left, Some(1.0)),
                    Token::Grower(mf),
                    Token::Pop,
                    Token::Grower(mf),
                ],
                plastic: None,
            }],
        );
        let l = ContinuousLimits::default();
        g.check_limits(&l).unwrap();
        let lsys = LSystem::from_text("t", &g.to_text()).unwrap();
        let mut dev = lsys.development(&DeriveOptions::default()).unwrap();
        while dev.advance().unwrap() {}
        let s = lsys.display(dev.current());
        assert_eq!(s.matches("mforward").count(), 32, "{s}");
        assert_eq!(s.matches("forward").count() - 32, 31, "{s}");
        // A rate that would mature faster than min_duration is refused.
        let mut fast = g.clone();
        fast.rules[0].rate = 0.4;
        assert!(fast.check_limits(&l).unwrap_err().contains("min_duration"));
    }
}
