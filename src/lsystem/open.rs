//! Open L-systems: `?E(mode, index, value)` modules exchange values with the environment.

use super::derive::Failure;
use super::string::{ModuleString, SymbolId};
use crate::environment::Environment;
use crate::lang::Span;

/// Processes the `?E` modules of `string` in string order: mode 0 writes `value` into
/// `env[index]`; mode 1 replaces the module's `value` with `env[index]`. `origins` says which
/// rule made which module (sorted by index), for error messages. Returns whether anything
/// changed (a value read or a slot written).
pub(crate) fn exchange(
    string: &mut ModuleString,
    query: SymbolId,
    env: &mut Environment,
    origins: &[(u32, Span)],
) -> Result<bool, Failure> {
    let mut changed = false;
    for i in 0..string.len() {
        if string.syms[i] != query {
            continue;
        }
        let start = string.bounds[i] as usize;
        let (mode, index, value) = (
            string.params[start],
            string.params[start + 1],
            string.params[start + 2],
        );
        let fail = |message: String| {
            let span = origins
                .binary_search_by_key(&(i as u32), |(at, _)| *at)
                .ok()
                .map(|k| origins[k].1);
            Failure::Query { span, message }
        };
        if index < 0.0 || index.fract() != 0.0 || index >= env.len() as f64 {
            return Err(fail(format!(
                "?E({mode}, {index}, {value}): index {index} is outside the environment of {} slot(s)",
                env.len()
            )));
        }
        let index = index as usize;
        if mode == 0.0 {
            changed |= env.get(index).expect("index checked") != value;
            env.set(index, value).expect("index checked");
        } else if mode == 1.0 {
            let read = env.get(index).expect("index checked");
            changed |= string.params[start + 2] != read;
            string.params[start + 2] = read;
        } else {
            return Err(fail(format!(
                "?E({mode}, {index}, {value}): mode must be 0 (write) or 1 (read)"
            )));
        }
    }
    Ok(changed)
}
