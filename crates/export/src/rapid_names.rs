//! Which identifiers a user may give a RAPID program (the heat's digital output, for
//! one): not a reserved word, not a predefined data type, instruction, function or data
//! object of the RAPID kernel, not a name the written modules declare. RAPID compares
//! identifiers without case, and so does [`name_problem`](crate::rapid_names::name_problem).
//!
//! The lists follow ABB's *Technical reference manual — RAPID kernel* (reserved words,
//! §"Reserved words") and *RAPID Instructions, Functions and Data types* (the names in
//! use in a hot-blade cell and the common ones besides).

/// RAPID's reserved words.
pub const RESERVED: &[&str] = &[
    "ALIAS",
    "AND",
    "BACKWARD",
    "CASE",
    "CONNECT",
    "CONST",
    "DEFAULT",
    "DIV",
    "DO",
    "ELSE",
    "ELSEIF",
    "ENDFOR",
    "ENDFUNC",
    "ENDIF",
    "ENDMODULE",
    "ENDPROC",
    "ENDRECORD",
    "ENDTEST",
    "ENDTRAP",
    "ENDWHILE",
    "ERROR",
    "EXIT",
    "FALSE",
    "FOR",
    "FROM",
    "FUNC",
    "GOTO",
    "IF",
    "INOUT",
    "LOCAL",
    "MOD",
    "MODULE",
    "NOSTEPIN",
    "NOT",
    "NOVIEW",
    "OR",
    "PERS",
    "PROC",
    "RAISE",
    "READONLY",
    "RECORD",
    "RETRY",
    "RETURN",
    "STEP",
    "SYSMODULE",
    "TEST",
    "THEN",
    "TO",
    "TRAP",
    "TRUE",
    "TRYNEXT",
    "UNDO",
    "VAR",
    "VIEWONLY",
    "WHILE",
    "WITH",
    "XOR",
];

/// Predefined data types.
pub const TYPES: &[&str] = &[
    "aiotrigg",
    "bool",
    "btnres",
    "busstate",
    "buttondata",
    "byte",
    "cameradev",
    "cfgdomain",
    "clock",
    "confdata",
    "corrdescr",
    "datapos",
    "dionum",
    "dir",
    "dnum",
    "errdomain",
    "errnum",
    "errstr",
    "errtype",
    "event_type",
    "exec_level",
    "extjoint",
    "handler_type",
    "icondata",
    "identno",
    "intnum",
    "iodev",
    "iounit_state",
    "jointtarget",
    "listitem",
    "loaddata",
    "loadidnum",
    "loadsession",
    "mecunit",
    "motsetdata",
    "num",
    "opcalc",
    "opnum",
    "orient",
    "paridnum",
    "paridvalidnum",
    "pathrecid",
    "pos",
    "pose",
    "progdisp",
    "rawbytes",
    "restartdata",
    "rmqheader",
    "rmqmessage",
    "rmqslot",
    "robjoint",
    "robtarget",
    "shapedata",
    "signalai",
    "signalao",
    "signaldi",
    "signaldo",
    "signalgi",
    "signalgo",
    "signalorigin",
    "speeddata",
    "stoppointdata",
    "string",
    "stringdig",
    "switch",
    "symnum",
    "syncident",
    "system_data",
    "taskid",
    "tasks",
    "testsignal",
    "tooldata",
    "tpnum",
    "trapdata",
    "triggdata",
    "triggflag",
    "triggios",
    "triggiosdnum",
    "triggstrgo",
    "tsp_status",
    "uishownum",
    "wobjdata",
    "wzstationary",
    "wztemporary",
    "zonedata",
];

/// Instructions and functions (those the modules use, and the common ones).
pub const ROUTINES: &[&str] = &[
    "AccSet",
    "ActUnit",
    "Add",
    "Break",
    "CallByVar",
    "Clear",
    "ClkReset",
    "ClkStart",
    "ClkStop",
    "Close",
    "ConfJ",
    "ConfL",
    "CorrClear",
    "DeactUnit",
    "Decr",
    "EOffsOff",
    "EOffsOn",
    "EOffsSet",
    "ErrWrite",
    "GripLoad",
    "IDelete",
    "IDisable",
    "IEnable",
    "Incr",
    "InvertDO",
    "ISignalDI",
    "ISignalDO",
    "ITimer",
    "IWatch",
    "Load",
    "MoveAbsJ",
    "MoveC",
    "MoveJ",
    "MoveL",
    "MoveLDO",
    "MoveLSync",
    "Open",
    "PathResol",
    "PDispOff",
    "PDispOn",
    "PulseDO",
    "Reset",
    "ResetRetryCount",
    "RestoPath",
    "Set",
    "SetAO",
    "SetDO",
    "SetGO",
    "SingArea",
    "SoftAct",
    "SpeedRefresh",
    "StartMove",
    "Stop",
    "StopMove",
    "StorePath",
    "SyncMoveOff",
    "SyncMoveOn",
    "SyncMoveUndo",
    "TPErase",
    "TPReadFK",
    "TPReadNum",
    "TPShow",
    "TPWrite",
    "TriggIO",
    "TriggL",
    "UnLoad",
    "VelSet",
    "WaitDI",
    "WaitDO",
    "WaitLoad",
    "WaitSyncTask",
    "WaitTime",
    "WaitUntil",
    "WaitWObj",
    "WorldAccLim",
    "Write",
    "WriteBin",
    "WriteStrBin",
    "Abs",
    "ACos",
    "AOutput",
    "ArgName",
    "ASin",
    "ATan",
    "ATan2",
    "BitAnd",
    "CalcJointT",
    "CalcRobT",
    "CDate",
    "CJointT",
    "ClkRead",
    "CorrRead",
    "Cos",
    "CPos",
    "CRobT",
    "CTime",
    "CTool",
    "CWObj",
    "DefDFrame",
    "DefFrame",
    "Dim",
    "Distance",
    "DInput",
    "DOutput",
    "EulerZYX",
    "Exp",
    "GetTime",
    "GOutput",
    "IsPers",
    "IsVar",
    "MirPos",
    "NOrient",
    "NumToStr",
    "Offs",
    "OrientZYX",
    "ORobT",
    "PoseInv",
    "PoseMult",
    "PoseVect",
    "Pow",
    "Present",
    "ReadNum",
    "ReadStr",
    "RelTool",
    "Round",
    "Sin",
    "Sqrt",
    "StrFind",
    "StrLen",
    "StrPart",
    "StrToVal",
    "Tan",
    "TestDI",
    "Trunc",
    "ValToStr",
    "VectMagn",
];

/// Predefined data objects.
pub const DATA: &[&str] = &["wobj0", "tool0", "load0", "load1", "vmax", "fine"];

/// Names the written modules declare or call (`crate::rapid`).
pub const OURS: &[&str] = &[
    "main",
    "change_block",
    "tlBlade",
    "idStart",
    "idSyncOn",
    "idSyncOff",
    "idEnd",
    "nAnswer",
    "vCut",
    "vAir",
    "wFixture",
    "tGrip",
    "wCarried",
    "stEmpty",
    "remove",
    "place",
];

/// `prefix` followed by digits only.
fn numbered(name: &str, prefix: &str) -> bool {
    name.strip_prefix(prefix)
        .is_some_and(|r| !r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()))
}

/// Whether `name` (lower case) follows a pattern of generated or predefined names:
/// `pB<n>_<letter><n>` (robtargets), `posBlock<n>`, `tBlade<n>`, `T_ROB<n>` and
/// `<module>_T_ROB<n>`, `ROB_<n>`, `v<n>` (speeddata), `z<n>` (zonedata).
fn generated(name: &str) -> bool {
    let robtarget = name.strip_prefix("pb").is_some_and(|r| {
        r.split_once('_').is_some_and(|(block, step)| {
            !block.is_empty()
                && block.bytes().all(|b| b.is_ascii_digit())
                && step.len() >= 2
                && step.as_bytes()[0].is_ascii_alphabetic()
                && step[1..].bytes().all(|b| b.is_ascii_digit())
        })
    });
    let task = name.rfind("t_rob").is_some_and(|i| {
        numbered(&name[i..], "t_rob") && (i == 0 || name.as_bytes()[i - 1] == b'_')
    });
    robtarget
        || task
        || ["posblock", "tblade", "rob_", "v", "z"]
            .iter()
            .any(|p| numbered(name, p))
}

/// Why `name` cannot be a user-given RAPID identifier (`None`: it can): not an identifier
/// (a letter, then letters, digits or `_`, at most 32), or a name RAPID or the modules
/// already give a meaning.
///
/// ```
/// use export::rapid_names::name_problem;
/// assert_eq!(name_problem("doHeat"), None);
/// assert!(name_problem("GOTO").is_some());
/// assert!(name_problem("setdo").is_some());
/// assert!(name_problem("pB1_C1").is_some());
/// assert!(name_problem("9lives").is_some());
/// ```
pub fn name_problem(name: &str) -> Option<String> {
    let identifier = name.len() <= 32
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !identifier {
        return Some(
            "is not a RAPID identifier (a letter, then letters, digits or _, at most 32)".into(),
        );
    }
    let is = |list: &[&str]| list.iter().any(|w| w.eq_ignore_ascii_case(name));
    let what = if is(RESERVED) {
        "a RAPID reserved word"
    } else if is(TYPES) {
        "a RAPID data type"
    } else if is(ROUTINES) {
        "a RAPID instruction or function"
    } else if is(DATA) {
        "predefined RAPID data"
    } else if is(OURS) || generated(&name.to_ascii_lowercase()) {
        "a name the written modules declare"
    } else {
        return None;
    };
    Some(format!("is {what} (RAPID ignores case)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taken_names_are_refused_in_any_case() {
        for n in [
            "GOTO",
            "exit",
            "Trap",
            "ERROR",
            "RAISE",
            "RETRY",
            "TEST",
            "ELSEIF",
            "FUNC",
            "LOCAL",
            "pB1_C1",
            "pb12_s3",
            "posBlock1",
            "num",
            "SetDO",
            "tBlade2",
            "T_ROB1",
            "job_T_ROB3",
            "v100",
            "z10",
            "ROB_1",
            "wobj0",
            "nAnswer",
        ] {
            assert!(name_problem(n).is_some(), "{n}");
        }
        for n in [
            "doHeat",
            "do_Heat1",
            "HeatOn",
            "pB",
            "posBlockA",
            "vCutter",
            "zone",
            "Rob1",
        ] {
            assert_eq!(name_problem(n), None, "{n}");
        }
        for n in ["", "1a", "a-b", "a b", &"a".repeat(33)] {
            assert!(name_problem(n).is_some(), "{n:?}");
        }
    }
}
