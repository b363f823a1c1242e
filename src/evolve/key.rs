//! The evaluation key: a SHA-256 hash of a developed creature and the task specification it
//! is evaluated with, over a canonical byte serialisation of both (every part, joint, neuron
//! and setting, every `f64` by its bits). An evaluation is a pure function of the creature
//! and the task, so two individuals with one key have one evaluation.
//!
//! Keys have versions ([`KeyVersion`]): version 2 hashes only what the task being run reads
//! (its name, the simulator's settings and its own settings, [`crate::task::Task::reads`]),
//! so that a setting of another task, or a new task, changes no key; version 1, which runs
//! made before it keep, hashed every task's settings, as the run's stored `[task]` table
//! holds them ([`EvaluationKey::of_tables`]).

use serde::ser::{self, Serialize};
use sha2::{Digest, Sha256};

use crate::creature::Creature;
use crate::sim::WorldSpec;
use crate::task::{CatapultOptions, JumpOptions, TaskSpec, TaskTables, Trials, WalkerOptions};

/// A creature-and-task key: 32 bytes, written as 64 lowercase hexadecimal digits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EvaluationKey(pub [u8; 32]);

/// Which bytes a key hashes besides the creature's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum KeyVersion {
    /// Every task's settings, side by side (`task`, `sim`, `walker`, `jump`, `catapult`), as
    /// the keys of runs made before version 2 were.
    V1,
    /// The task's name, the simulator's settings and the task's own settings: the keys of
    /// every run started today.
    #[default]
    V2,
}

/// The task specification as version 1 hashed it: every task's settings of its day.
#[derive(serde::Serialize)]
struct SpecV1<'a> {
    task: crate::task::TaskKind,
    sim: &'a crate::sim::SimOptions,
    walker: &'a WalkerOptions,
    jump: &'a JumpOptions,
    catapult: &'a CatapultOptions,
}

/// The task specification as version 2 hashes it: what the task reads.
#[derive(serde::Serialize)]
struct SpecV2<'a, O: Serialize> {
    key_version: u8,
    task: crate::task::TaskKind,
    sim: &'a crate::sim::SimOptions,
    options: O,
}

impl EvaluationKey {
    /// The key of evaluating `creature` with `task`, of today's version ([`KeyVersion::V2`]).
    pub fn of(creature: &Creature, task: &TaskSpec) -> EvaluationKey {
        EvaluationKey::of_version(creature, task, KeyVersion::default())
    }

    /// The key of evaluating `creature` with `task`, of version `version` (version 1 with
    /// the other tasks' default settings: [`EvaluationKey::of_tables`] takes them as stored).
    pub fn of_version(creature: &Creature, task: &TaskSpec, version: KeyVersion) -> EvaluationKey {
        match version {
            KeyVersion::V1 => EvaluationKey::of_tables(creature, &TaskTables::from(task)),
            KeyVersion::V2 => EvaluationKey::hash(creature, &task.world, |hasher| {
                crate::with_options!(&task.task, T, o => SpecV2 {
                    key_version: 2,
                    task: task.kind(),
                    sim: &task.sim,
                    options: <T as crate::task::Task>::reads(o),
                }
                .serialize(hasher))
            }),
        }
    }

    /// The version 1 key of evaluating `creature` with the task `tables` names: it hashed
    /// the walker's, the jump's and the catapult's settings side by side, as `tables` holds
    /// them (each task's defaults where it holds none).
    pub fn of_tables(creature: &Creature, tables: &TaskTables) -> EvaluationKey {
        EvaluationKey::hash(creature, &tables.world, |hasher| {
            SpecV1 {
                task: tables.kind(),
                sim: &tables.sim,
                walker: &tables.get::<WalkerOptions>().cloned().unwrap_or_default(),
                jump: &tables.get::<JumpOptions>().cloned().unwrap_or_default(),
                catapult: &tables.get::<CatapultOptions>().cloned().unwrap_or_default(),
            }
            .serialize(hasher)
        })
    }

    /// The hash of `creature`, then of what `task` feeds the hasher, then of `world`.
    fn hash(
        creature: &Creature,
        world: &WorldSpec,
        task: impl FnOnce(&mut CanonicalHasher) -> Result<(), HashError>,
    ) -> EvaluationKey {
        let mut hasher = CanonicalHasher(Sha256::new());
        // Serialising plain data into a hasher cannot fail: every value has a byte form.
        creature
            .serialize(&mut hasher)
            .and_then(|()| task(&mut hasher))
            // A world other than flat ground joins the key; a flat one adds nothing, so the
            // keys of every run made before worlds existed stay as they were.
            .and_then(|()| match world.is_flat() {
                true => Ok(()),
                false => world.serialize(&mut hasher),
            })
            .expect("every creature and task serialises");
        EvaluationKey(hasher.0.finalize().into())
    }

    /// The key of an individual developed into `creatures`, one per habitat of `task` (in
    /// the order of `[[task.habitats]]`), of version `version`. A plain specification (no
    /// habitats, the default trials) gives its one creature's key
    /// ([`EvaluationKey::of_version`]), so no key made before habitats changes; otherwise the
    /// key hashes each habitat's key (its creature with [`TaskSpec::in_habitat`]), each
    /// habitat's name and array, and the trials (and each habitat's trials,
    /// [`TaskSpec::trials_in`], when one sets its own noise ranges).
    pub fn of_habitats(
        creatures: &[Creature],
        task: &TaskSpec,
        version: KeyVersion,
    ) -> EvaluationKey {
        if task.is_plain() && creatures.len() == 1 {
            return EvaluationKey::of_version(&creatures[0], task, version);
        }
        let mut hasher = CanonicalHasher(Sha256::new());
        let keys: Vec<[u8; 32]> = creatures
            .iter()
            .enumerate()
            .map(|(h, c)| EvaluationKey::of_version(c, &task.in_habitat(h), version).0)
            .collect();
        let habitats: Vec<(&str, Option<&[f64]>)> = (0..creatures.len())
            .map(|h| (task.habitat_name(h), task.habitat_environment(h)))
            .collect();
        // A habitat's own noise ranges join the key only when some habitat sets them, so no
        // key made before habitats could set them changes.
        let own_noise = task.habitats.iter().any(|h| h.trials.is_some());
        if own_noise {
            let trials: Vec<Trials> = (0..creatures.len()).map(|h| task.trials_in(h)).collect();
            ("habitats", keys, habitats, &task.trials, trials).serialize(&mut hasher)
        } else {
            ("habitats", keys, habitats, &task.trials).serialize(&mut hasher)
        }
        .expect("every creature and task serialises");
        EvaluationKey(hasher.0.finalize().into())
    }

    /// This key (of the creatures `genome` develops into) for a task whose creatures go on
    /// developing during their evaluation (`develop = "during"`): the creature dropped does
    /// not say how it grows, so the key hashes this one with the development's settings
    /// (`develop`, `develop_rate`, `develop_t0` when set) and the genome's text. A task whose
    /// creatures develop before their evaluation keeps this key as it is, so no key of a run
    /// without `develop` changes.
    pub fn growing<G: crate::encoding::Genome>(self, task: &TaskSpec, genome: &G) -> EvaluationKey {
        self.growing_text(task, &genome.to_text())
    }

    /// [`EvaluationKey::growing`] of a genome whose text is `text` (or of a grammar file's
    /// text, for a grammar that is no run's genome).
    pub fn growing_text(self, task: &TaskSpec, text: &str) -> EvaluationKey {
        if !task.develop.during() {
            return self;
        }
        let mut hasher = CanonicalHasher(Sha256::new());
        (
            "develop",
            self.0,
            task.develop.when,
            task.develop.rate,
            task.develop.t0,
            text,
        )
            .serialize(&mut hasher)
            .expect("every key and setting serialises");
        EvaluationKey(hasher.0.finalize().into())
    }

    /// The key as 64 lowercase hexadecimal digits, as the run store keeps it.
    pub fn to_hex(&self) -> String {
        self.0.iter().map(|b| format!("{b:02x}")).collect()
    }

    /// The key written by [`EvaluationKey::to_hex`]; `None` if `text` is not 64 hex digits.
    pub fn from_hex(text: &str) -> Option<EvaluationKey> {
        if text.len() != 64 || !text.is_ascii() {
            return None;
        }
        let mut bytes = [0u8; 32];
        for (i, b) in bytes.iter_mut().enumerate() {
            *b = u8::from_str_radix(&text[2 * i..2 * i + 2], 16).ok()?;
        }
        Some(EvaluationKey(bytes))
    }
}

/// A serde serialiser that feeds a canonical byte form of a value to SHA-256: each value is
/// a type tag then its bytes (numbers little-endian, floats by their bits, strings and
/// sequences after their length), so distinct values give distinct byte streams.
struct CanonicalHasher(Sha256);

/// Serialisation into a hasher never fails; serde requires an error type all the same.
#[derive(Debug)]
struct HashError(String);

impl std::fmt::Display for HashError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for HashError {}

impl ser::Error for HashError {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        HashError(msg.to_string())
    }
}

impl CanonicalHasher {
    fn tag(&mut self, tag: u8) {
        self.0.update([tag]);
    }

    fn bytes(&mut self, tag: u8, bytes: &[u8]) {
        self.tag(tag);
        self.0.update((bytes.len() as u64).to_le_bytes());
        self.0.update(bytes);
    }

    fn variant(&mut self, tag: u8, index: u32, variant: &str) {
        self.bytes(tag, &index.to_le_bytes());
        self.bytes(tag, variant.as_bytes());
    }

    fn length(&mut self, tag: u8, len: Option<usize>) {
        self.tag(tag);
        // Sequences of unknown length end with a terminator tag instead.
        self.0
            .update((len.map_or(u64::MAX, |n| n as u64)).to_le_bytes());
    }
}

/// Serialiser methods for narrow integers: each widens to its 64-bit form, so a number
/// hashes alike whatever width it is stored in.
macro_rules! widened {
    ($($method:ident($narrow:ty) => $wide:ident),* $(,)?) => {
        $(
            fn $method(self, v: $narrow) -> Result<(), HashError> {
                self.$wide(v.into())
            }
        )*
    };
}

/// Serialiser methods for numbers hashed as a type tag and the little-endian bytes of an
/// integer (a float's bits, a character's code point).
macro_rules! little_endian {
    ($($method:ident($v:ident: $ty:ty) => $tag:expr, $bits:expr),* $(,)?) => {
        $(
            fn $method(self, $v: $ty) -> Result<(), HashError> {
                self.bytes($tag, &$bits.to_le_bytes());
                Ok(())
            }
        )*
    };
}

/// Serialiser methods for enum variants with fields: a type tag, the variant's index and
/// name, then the number of fields.
macro_rules! variants_with_length {
    ($($method:ident => $tag:expr),* $(,)?) => {
        $(
            fn $method(
                self,
                _name: &'static str,
                index: u32,
                variant: &'static str,
                len: usize,
            ) -> Result<Self, HashError> {
                self.variant($tag, index, variant);
                self.length($tag, Some(len));
                Ok(self)
            }
        )*
    };
}

impl ser::Serializer for &mut CanonicalHasher {
    type Ok = ();
    type Error = HashError;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Self;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    fn serialize_bool(self, v: bool) -> Result<(), HashError> {
        self.bytes(1, &[v as u8]);
        Ok(())
    }
    widened! {
        serialize_i8(i8) => serialize_i64,
        serialize_i16(i16) => serialize_i64,
        serialize_i32(i32) => serialize_i64,
        serialize_u8(u8) => serialize_u64,
        serialize_u16(u16) => serialize_u64,
        serialize_u32(u32) => serialize_u64,
    }
    little_endian! {
        serialize_i64(v: i64) => 2, v,
        serialize_i128(v: i128) => 3, v,
        serialize_u64(v: u64) => 4, v,
        serialize_u128(v: u128) => 5, v,
        serialize_f32(v: f32) => 6, v.to_bits(),
        serialize_f64(v: f64) => 7, v.to_bits(),
        serialize_char(v: char) => 8, u32::from(v),
    }
    fn serialize_str(self, v: &str) -> Result<(), HashError> {
        self.bytes(9, v.as_bytes());
        Ok(())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<(), HashError> {
        self.bytes(10, v);
        Ok(())
    }
    fn serialize_none(self) -> Result<(), HashError> {
        self.tag(11);
        Ok(())
    }
    fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> Result<(), HashError> {
        self.tag(12);
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), HashError> {
        self.tag(13);
        Ok(())
    }
    fn serialize_unit_struct(self, name: &'static str) -> Result<(), HashError> {
        self.bytes(14, name.as_bytes());
        Ok(())
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        index: u32,
        variant: &'static str,
    ) -> Result<(), HashError> {
        self.variant(15, index, variant);
        Ok(())
    }
    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<(), HashError> {
        self.tag(16);
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), HashError> {
        self.variant(17, index, variant);
        value.serialize(self)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Self, HashError> {
        self.length(18, len);
        Ok(self)
    }
    fn serialize_tuple(self, len: usize) -> Result<Self, HashError> {
        self.length(19, Some(len));
        Ok(self)
    }
    fn serialize_tuple_struct(self, _name: &'static str, len: usize) -> Result<Self, HashError> {
        self.length(20, Some(len));
        Ok(self)
    }
    fn serialize_map(self, len: Option<usize>) -> Result<Self, HashError> {
        self.length(22, len);
        Ok(self)
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<Self, HashError> {
        self.length(23, Some(len));
        Ok(self)
    }
    variants_with_length! {
        serialize_tuple_variant => 21,
        serialize_struct_variant => 24,
    }
}

/// The end of a sequence, map or struct.
const END: u8 = 0xFF;

macro_rules! compound {
    ($trait:ident, $method:ident) => {
        impl ser::$trait for &mut CanonicalHasher {
            type Ok = ();
            type Error = HashError;
            fn $method<T: ?Sized + Serialize>(&mut self, value: &T) -> Result<(), HashError> {
                value.serialize(&mut **self)
            }
            fn end(self) -> Result<(), HashError> {
                self.tag(END);
                Ok(())
            }
        }
    };
}

compound!(SerializeSeq, serialize_element);
compound!(SerializeTuple, serialize_element);
compound!(SerializeTupleStruct, serialize_field);
compound!(SerializeTupleVariant, serialize_field);

impl ser::SerializeMap for &mut CanonicalHasher {
    type Ok = ();
    type Error = HashError;
    fn serialize_key<T: ?Sized + Serialize>(&mut self, key: &T) -> Result<(), HashError> {
        key.serialize(&mut **self)
    }
    fn serialize_value<T: ?Sized + Serialize>(&mut self, value: &T) -> Result<(), HashError> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), HashError> {
        self.tag(END);
        Ok(())
    }
}

/// The name a field is hashed under: its own, but for a renamed one
/// ([`crate::sim::RENAMED_KEYS`]: the control step, [`crate::sim::SimOptions::control_step`]),
/// which is hashed under the name it had before (`dt`), so that the keys of older run stores
/// still match and a resumed run reuses what it did before.
fn hashed_name(key: &'static str) -> &'static str {
    crate::sim::RENAMED_KEYS
        .iter()
        .find(|(today, _)| *today == key)
        .map_or(key, |(_, before)| before)
}

/// Fields that a release added to settings and creatures that keys hash, written (and
/// hashed) only when set: a task's fitness expression (`fitness` of the jump's, catapult's,
/// stand's and swim's tables; the walker's `fitness` is always written), the catapult's
/// `evolve_projectile` and `target_sensor` (written when not their defaults), and a
/// creature's own `projectile`. Unset, such a field adds nothing to the key, so that the keys
/// of every configuration and creature without it stay as they were.
const ADDED_WHEN_SET: &[&str] = &[
    "fitness",
    "evolve_projectile",
    "target_sensor",
    "projectile",
];

macro_rules! fields {
    ($trait:ident) => {
        impl ser::$trait for &mut CanonicalHasher {
            type Ok = ();
            type Error = HashError;
            fn serialize_field<T: ?Sized + Serialize>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), HashError> {
                self.bytes(25, hashed_name(key).as_bytes());
                value.serialize(&mut **self)
            }
            fn skip_field(&mut self, key: &'static str) -> Result<(), HashError> {
                if !ADDED_WHEN_SET.contains(&key) {
                    self.bytes(26, hashed_name(key).as_bytes());
                }
                Ok(())
            }
            fn end(self) -> Result<(), HashError> {
                self.tag(END);
                Ok(())
            }
        }
    };
}

fields!(SerializeStruct);
fields!(SerializeStructVariant);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::TaskKind;

    #[test]
    fn a_key_reads_back_from_its_hex_form() {
        let key = EvaluationKey::of(&Creature::default(), &TaskSpec::new(TaskKind::Walker));
        assert_eq!(key.to_hex().len(), 64);
        assert_eq!(EvaluationKey::from_hex(&key.to_hex()), Some(key));
        assert_eq!(EvaluationKey::from_hex("zz"), None);
    }

    #[test]
    fn a_key_changes_with_the_last_bit_of_a_value_and_with_the_task() {
        let task = TaskSpec::new(TaskKind::Walker);
        let mut creature = Creature {
            environment: vec![0.5],
            ..Creature::default()
        };
        let key = EvaluationKey::of(&creature, &task);
        assert_eq!(EvaluationKey::of(&creature.clone(), &task), key);
        creature.environment[0] = f64::from_bits(0.5f64.to_bits() + 1);
        assert_ne!(EvaluationKey::of(&creature, &task), key);
        creature.environment[0] = 0.5;
        assert_ne!(
            EvaluationKey::of(&creature, &TaskSpec::new(TaskKind::Jump)),
            key
        );
    }

    #[test]
    fn the_control_step_is_hashed_under_its_old_name() {
        // Run stores written when the control step was serialised as `dt` hold keys that a
        // resumed run must still match.
        #[derive(serde::Serialize)]
        struct Old {
            dt: f64,
        }
        #[derive(serde::Serialize)]
        struct New {
            #[serde(rename = "control_step")]
            dt: f64,
        }
        let hash = |value: &dyn Fn(&mut CanonicalHasher) -> Result<(), HashError>| {
            let mut hasher = CanonicalHasher(Sha256::new());
            value(&mut hasher).unwrap();
            hasher.0.finalize()
        };
        let old = hash(&|h| Old { dt: 0.02 }.serialize(h));
        assert_eq!(hash(&|h| New { dt: 0.02 }.serialize(h)), old);
        assert_ne!(hash(&|h| New { dt: 0.03 }.serialize(h)), old);
    }
}
