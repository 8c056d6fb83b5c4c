//! Run-time choices made by name (approximator, rule, experiment). Each is an enum deriving
//! strum's `Display`, `IntoStaticStr` and `VariantArray`, serde and (with the `cli` feature)
//! `clap::ValueEnum`, all with kebab-case names, so the command line, run ids and
//! `summary.json` can never disagree about a spelling. [`Named`] adds the lookups.

/// Name lookups for an enum of named choices (blanket-implemented).
pub trait Named: Copy + PartialEq + strum::VariantArray + Into<&'static str> + 'static {
    /// The name used on the command line, in run ids and in `summary.json`.
    fn name(self) -> &'static str {
        self.into()
    }

    /// The choice called `name`, if any.
    fn from_name(name: &str) -> Option<Self> {
        Self::VARIANTS.iter().copied().find(|k| k.name() == name)
    }

    /// Every name, for messages: `"a, b or c"`.
    fn names() -> String {
        let all: Vec<&str> = Self::VARIANTS.iter().map(|k| k.name()).collect();
        match all.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => all.join(""),
        }
    }
}

impl<T: Copy + PartialEq + strum::VariantArray + Into<&'static str> + 'static> Named for T {}

#[cfg(test)]
mod tests {
    use super::Named;
    use strum::VariantArray;

    /// A test choice.
    #[derive(
        Debug,
        Clone,
        Copy,
        PartialEq,
        serde::Serialize,
        serde::Deserialize,
        strum::Display,
        strum::IntoStaticStr,
        strum::VariantArray,
    )]
    #[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
    #[serde(rename_all = "kebab-case")]
    #[strum(serialize_all = "kebab-case")]
    enum Colour {
        Red,
        DarkBlue,
        Green,
    }

    #[test]
    fn names_agree_across_serde_display_and_lookup() {
        assert_eq!(
            Colour::VARIANTS,
            [Colour::Red, Colour::DarkBlue, Colour::Green]
        );
        for &c in Colour::VARIANTS {
            assert_eq!(Colour::from_name(c.name()), Some(c));
            assert_eq!(c.to_string(), c.name());
            assert_eq!(
                serde_json::to_string(&c).unwrap(),
                format!("\"{}\"", c.name())
            );
            #[cfg(feature = "cli")]
            {
                use clap::ValueEnum;
                assert_eq!(c.to_possible_value().unwrap().get_name(), c.name());
            }
        }
        assert_eq!(Colour::DarkBlue.name(), "dark-blue");
        assert_eq!(Colour::from_name("blue"), None);
        assert_eq!(Colour::names(), "red, dark-blue or green");
        assert!(serde_json::from_str::<Colour>("\"DarkBlue\"").is_err());
    }
}
