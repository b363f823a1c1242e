//! Module strings: the symbols and parameters an L-system derives, stored flat.

use std::collections::HashMap;

use serde::Serialize;

use crate::number::format_number;

/// The index of a module name in a [`SymbolTable`].
pub type SymbolId = u32;

/// The id of `[` in every symbol table.
pub const PUSH: SymbolId = 0;
/// The id of `]` in every symbol table.
pub const POP: SymbolId = 1;

/// Module names, interned. `[` and `]` always have the ids [`PUSH`] and [`POP`].
#[derive(Clone, Debug)]
pub struct SymbolTable {
    names: Vec<String>,
    ids: HashMap<String, SymbolId>,
}

impl Default for SymbolTable {
    fn default() -> Self {
        let mut table = SymbolTable {
            names: Vec::new(),
            ids: HashMap::new(),
        };
        table.intern("[");
        table.intern("]");
        table
    }
}

impl SymbolTable {
    /// The id of `name`, adding it if new.
    pub fn intern(&mut self, name: &str) -> SymbolId {
        if let Some(&id) = self.ids.get(name) {
            return id;
        }
        let id = SymbolId::try_from(self.names.len()).expect("fewer than 2^32 module names");
        self.names.push(name.to_string());
        self.ids.insert(name.to_string(), id);
        id
    }

    /// The id of `name`, if it is known.
    pub fn id(&self, name: &str) -> Option<SymbolId> {
        self.ids.get(name).copied()
    }

    /// The name of `id`.
    pub fn name(&self, id: SymbolId) -> &str {
        &self.names[id as usize]
    }

    /// How many names there are.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether there are no names (never true: `[` and `]` are always present).
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
}

/// A string of modules. Symbols and parameters live in flat arrays, so deriving a step
/// appends to three vectors and never allocates per module.
#[derive(Clone, Debug, PartialEq)]
pub struct ModuleString {
    pub(crate) syms: Vec<SymbolId>,
    /// `bounds[i]..bounds[i + 1]` are module i's parameters; `bounds[0] == 0`.
    pub(crate) bounds: Vec<u32>,
    pub(crate) params: Vec<f64>,
}

/// One module of a [`ModuleString`], borrowed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Module<'a> {
    /// The module's symbol.
    pub sym: SymbolId,
    /// Its parameters.
    pub params: &'a [f64],
}

impl Default for ModuleString {
    fn default() -> Self {
        ModuleString::new()
    }
}

impl ModuleString {
    /// Whether `other` holds the same modules with the same parameters, bit for bit (`0` and
    /// `-0` differ, a NaN equals itself).
    pub fn same_bits(&self, other: &ModuleString) -> bool {
        self.syms == other.syms
            && self.bounds == other.bounds
            && self.params.len() == other.params.len()
            && self
                .params
                .iter()
                .zip(&other.params)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// The first `n` modules (all of them when there are fewer).
    pub fn prefix(&self, n: usize) -> ModuleString {
        let n = n.min(self.len());
        let end = self.bounds[n] as usize;
        ModuleString {
            syms: self.syms[..n].to_vec(),
            params: self.params[..end].to_vec(),
            bounds: self.bounds[..=n].to_vec(),
        }
    }

    /// An empty string.
    pub fn new() -> Self {
        ModuleString {
            syms: Vec::new(),
            bounds: vec![0],
            params: Vec::new(),
        }
    }

    /// An empty string with room for `modules` modules and `params` parameters.
    pub fn with_capacity(modules: usize, params: usize) -> Self {
        let mut bounds = Vec::with_capacity(modules + 1);
        bounds.push(0);
        ModuleString {
            syms: Vec::with_capacity(modules),
            bounds,
            params: Vec::with_capacity(params),
        }
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.syms.len()
    }

    /// Whether there are no modules.
    pub fn is_empty(&self) -> bool {
        self.syms.is_empty()
    }

    /// Removes every module, keeping the memory.
    pub fn clear(&mut self) {
        self.syms.clear();
        self.bounds.truncate(1);
        self.params.clear();
    }

    /// Appends a module.
    pub fn push(&mut self, sym: SymbolId, params: &[f64]) {
        self.syms.push(sym);
        self.params.extend_from_slice(params);
        self.bounds.push(self.params_len());
    }

    /// The symbol of module `i`.
    #[inline]
    pub fn sym(&self, i: usize) -> SymbolId {
        self.syms[i]
    }

    /// The parameters of module `i`.
    #[inline]
    pub fn params(&self, i: usize) -> &[f64] {
        &self.params[self.bounds[i] as usize..self.bounds[i + 1] as usize]
    }

    /// Module `i`.
    pub fn get(&self, i: usize) -> Module<'_> {
        Module {
            sym: self.syms[i],
            params: self.params(i),
        }
    }

    /// The modules in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Module<'_>> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The symbols in order.
    pub fn symbols(&self) -> &[SymbolId] {
        &self.syms
    }

    #[inline]
    pub(crate) fn params_len(&self) -> u32 {
        // Derivation checks the module limit, which keeps this far below u32::MAX.
        self.params.len() as u32
    }

    /// Copies module `i` of `other` onto the end.
    #[inline]
    pub(crate) fn push_from(&mut self, other: &ModuleString, i: usize) {
        self.push(other.syms[i], other.params(i));
    }

    /// Writes the string readably: one-character names run together, longer names stand
    /// apart, parameters in parentheses (`F[+F]F`, `B(1)B(4)A(1,0)`, `forward(1) revolute1`).
    pub fn display(&self, symbols: &SymbolTable) -> String {
        let mut out = String::with_capacity(self.len() * 2);
        let mut previous_long = false;
        for (i, m) in self.iter().enumerate() {
            let name = symbols.name(m.sym);
            let long = name.chars().count() > 1;
            if i > 0 && (long || previous_long) {
                out.push(' ');
            }
            out.push_str(name);
            if !m.params.is_empty() {
                out.push('(');
                for (k, p) in m.params.iter().enumerate() {
                    if k > 0 {
                        out.push(',');
                    }
                    out.push_str(&format_number(*p));
                }
                out.push(')');
            }
            previous_long = long;
        }
        out
    }

    /// The string as serialisable modules (`{"sym": "A", "params": [1.0]}`).
    pub fn to_modules<'a>(&'a self, symbols: &'a SymbolTable) -> Vec<NamedModule<'a>> {
        self.iter()
            .map(|m| NamedModule {
                sym: symbols.name(m.sym),
                params: m.params,
            })
            .collect()
    }
}

/// A module with its name spelled out, for JSON output.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct NamedModule<'a> {
    /// The module's name.
    pub sym: &'a str,
    /// Its parameters.
    pub params: &'a [f64],
}
