//! Mutations of valid files, for the tests that feed mutated files to a
//! loader: a fixed-seed xorshift generator, so that a failure reproduces,
//! and splices, deletions, replacements and truncations of the text.

/// A xorshift64 generator; its state is the seed (non-zero).
pub struct Rng(pub u64);

impl Rng {
    /// The next number of the sequence.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number in 0..n (0 for n = 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}

/// Fragments that tend to reach deep code paths when spliced in.
const PIECES: &[&str] = &[
    "\"",
    "[",
    "]",
    "{",
    "}",
    ",",
    "=",
    ":",
    "\n",
    "-",
    "0",
    "1e308",
    "-1e400",
    "nan",
    "inf",
    "\"1/0\"",
    "\"deg(\"",
    "\"x\"",
    "\"ground\"",
    "[[joints]]\ntype = \"gear\"\n",
    "[[bodies]]\nname = \"k\"\n",
    "\u{e9}",
    "\"t*t\"",
    "\"\"",
    "null",
    "true",
    "[0, 0]",
    "\"a.b\"",
    "\"crank.A\"",
];

/// `text` with one to three mutations at places `rng` draws: a character
/// removed, one of the fragments above spliced in, up to 40 characters removed,
/// a character replaced by a printable one, or the rest cut off.
pub fn mutate(rng: &mut Rng, text: &str) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.below(3) {
        let k = rng.below(chars.len() + 1);
        match rng.below(5) {
            0 if k < chars.len() => {
                chars.remove(k);
            }
            1 => {
                let piece = PIECES[rng.below(PIECES.len())];
                for (n, c) in piece.chars().enumerate() {
                    chars.insert(k + n, c);
                }
            }
            2 if k < chars.len() => {
                let end = (k + 1 + rng.below(40)).min(chars.len());
                chars.drain(k..end);
            }
            3 if k < chars.len() => {
                chars[k] = (b' ' + rng.below(95) as u8) as char;
            }
            _ => chars.truncate(k),
        }
    }
    chars.into_iter().collect()
}
