"""imunoise.read and the preprocessing keywords of imunoise.dev / imunoise.fit.

Files are written here by the real libraries (python3-h5py, python3-rosbag: Debian packages) and
in the EuRoC layout, and read back to the bit; the preprocessing keywords must give the same
document as the command line (the same library pipeline), and a gap split must agree with the
gap-free record within its intervals."""
import json
import math
import os
import shutil
import subprocess

import numpy as np
import pytest

import imunoise

RATE = 200.0
START_NS = 1_700_000_000_123_456_789


def imu_values(n, seed=16):
    rng = np.random.default_rng(seed)
    return rng.standard_normal((n, 6)) * [1e-3, 1e-3, 1e-3, 0.05, 0.05, 0.05] + [0, 0, 0, 0, 0, 9.81]


def test_bag_written_by_rosbag_reads_back_bit_for_bit(tmp_path):
    rosbag = pytest.importorskip("rosbag")
    rospy = pytest.importorskip("rospy")
    from sensor_msgs.msg import Imu
    from std_msgs.msg import String

    n = 3000
    values = imu_values(n)
    period_ns = int(round(1e9 / RATE))
    path = str(tmp_path / "imu.bag")
    with rosbag.Bag(path, "w", compression="lz4", chunk_threshold=16 * 1024) as bag:
        for i in range(n):
            stamp_ns = START_NS + i * period_ns
            msg = Imu()
            msg.header.seq = i
            msg.header.stamp = rospy.Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
            msg.header.frame_id = "imu_link"
            g = values[i]
            msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = g[0], g[1], g[2]
            msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = g[3], g[4], g[5]
            bag.write("/imu/data", msg, msg.header.stamp)
            if i % 1000 == 0:
                bag.write("/status", String(data="ok"), msg.header.stamp)
    rec = imunoise.read(path, topic="/imu/data")
    assert isinstance(rec, imunoise.Recording)
    assert rec.format == "ROS 1 bag" and rec.stream == "/imu/data" and rec.source == path
    assert rec.message_type == "sensor_msgs/Imu"
    assert rec.channel_names == ["gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"]
    assert rec.units["gyro_x"] == "rad/s" and rec.units["accel_z"] == "m/s^2"
    assert len(rec) == n
    np.testing.assert_array_equal(rec.to_array(), values)  # bit for bit
    np.testing.assert_array_equal(rec["gyro_y"], values[:, 1])
    np.testing.assert_array_equal(rec.channel(5), values[:, 5])
    # Integer nanoseconds since the first stamp, to 1 ns (here: to 1 ps).
    np.testing.assert_allclose(rec.time_s, np.arange(n) * period_ns * 1e-9, rtol=0, atol=1e-12)
    assert rec.rate == pytest.approx(RATE, rel=1e-12)
    assert rec.time_origin == f"{START_NS} ns"
    assert rec.gaps == []
    # column= keeps only those channels.
    only = imunoise.read(path, topic="/imu/data", column=["gyro_z", "accel_x"])
    assert only.channel_names == ["gyro_z", "accel_x"]
    # A wrong topic lists what the bag holds; a topic of another type says which type it is.
    with pytest.raises(ValueError, match="/imu/data"):
        imunoise.read(path, topic="/imu")
    with pytest.raises(ValueError, match="std_msgs/String"):
        imunoise.read(path, topic="/status")


def test_hdf5_written_by_h5py_reads_back_bit_for_bit(tmp_path):
    h5py = pytest.importorskip("h5py")
    n = 2000
    rng = np.random.default_rng(5)
    gyro = rng.standard_normal((n, 3)) * 1e-3
    counts = rng.integers(-30000, 30000, n).astype(np.int16)
    time = 1_600_000_000_000_000_000 + np.arange(n, dtype=np.int64) * 10_000_000
    path = str(tmp_path / "imu.h5")
    with h5py.File(path, "w") as f:
        d = f.create_dataset("imu/gyro", data=gyro)
        d.attrs["units"] = "rad/s"
        f.create_dataset("imu/time", data=time)
        f.create_dataset("counts", data=counts)
    rec = imunoise.read(path, dataset="/imu/gyro", time_dataset="/imu/time")
    assert rec.format == "HDF5" and rec.stream == "/imu/gyro"
    assert len(rec.channel_names) == 3
    assert all(u == "rad/s" for u in rec.units.values())
    np.testing.assert_array_equal(rec.to_array(), gyro)
    assert rec.rate == pytest.approx(100.0, rel=1e-12)
    plain = imunoise.read(path, dataset="counts", rate=50.0)
    np.testing.assert_array_equal(plain.channel(0), counts.astype(np.float64))
    assert plain.time_s is None and plain.rate == 50.0
    assert list(plain.units.values()) == [None]
    with pytest.raises(ValueError, match="imu/gyro"):
        imunoise.read(path, dataset="/nope")


def write_euroc(path, values, stamps_ns):
    with open(path, "w") as f:
        f.write("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n")
        for t, row in zip(stamps_ns, values):
            f.write(str(int(t)) + "," + ",".join(repr(float(v)) for v in row) + "\n")


def test_euroc_layout_and_text(tmp_path):
    n = 1000
    values = imu_values(n, seed=3)
    stamps = 1403636579758555392 + np.arange(n, dtype=np.int64) * 5_000_000
    folder = tmp_path / "mav0" / "imu0"
    folder.mkdir(parents=True)
    path = str(folder / "data.csv")
    write_euroc(path, values, stamps)
    rec = imunoise.read(path)
    assert rec.format == "EuRoC CSV"
    assert rec.channel_names[:3] == ["gyro_x", "gyro_y", "gyro_z"]
    assert rec.units["gyro_x"] == "rad/s" and rec.units["accel_x"] == "m/s^2"
    np.testing.assert_array_equal(rec.to_array(), values)  # repr() round-trips doubles exactly
    assert rec.rate == pytest.approx(200.0, rel=1e-12)
    assert rec.time_origin == "1403636579758555392 ns"
    # A text file: columns by header name, time column, no units.
    text = tmp_path / "t.csv"
    with open(text, "w") as f:
        f.write("t,gx,temp\n")
        for i in range(n):
            f.write(f"{i / 100:.2f},{values[i, 0]!r},{20 + i / n!r}\n")
    t = imunoise.read(str(text), column=["gx", "temp"], time_column="t")
    assert t.format == "text" and t.channel_names == ["gx", "temp"]
    np.testing.assert_array_equal(t["gx"], values[:, 0])
    assert t.units == {"gx": None, "temp": None}
    assert t.rate == pytest.approx(100.0, rel=1e-9)
    with pytest.raises(ValueError, match="no such file"):
        imunoise.read(str(tmp_path / "missing.bag"), topic="/imu")


def test_binary_needs_a_rate_and_reads_its_channels(tmp_path):
    data = np.arange(12, dtype="<f4").reshape(6, 2)
    path = str(tmp_path / "x.f32")
    data.tofile(path)
    rec = imunoise.read(path, channels=2, rate=10.0)
    assert rec.format == "binary" and rec.channel_names == ["channel 0", "channel 1"]
    np.testing.assert_array_equal(rec.to_array(), data.astype(np.float64))
    assert rec.rate == 10.0 and rec.time_s is None


@pytest.fixture(scope="module")
def gappy():
    """1 h at 100 Hz of white rate noise (sd 1e-3 rad/s) plus a slow random walk, with 5 s missing
    at 30 min: (full values, values with the gap, their timestamps)."""
    rng = np.random.default_rng(7)
    n = 360_000
    v = rng.standard_normal(n) * 1e-3 + np.cumsum(rng.standard_normal(n)) * 2e-7
    t = np.arange(n) / 100.0
    keep = np.ones(n, dtype=bool)
    keep[180_000:180_500] = False
    return v, v[keep], t[keep]


def test_gap_refused_then_split_agrees_with_the_gap_free_record(gappy):
    full, cut, t = gappy
    with pytest.raises(ValueError, match="gap"):
        imunoise.dev(cut, time=t)
    for estimator in ["adev", "oadev", "mdev", "tdev", "hdev", "ohdev"]:
        whole = imunoise.dev(full, 100.0, estimators=estimator, units="rad/s", level=0.95)
        split = imunoise.dev(cut, time=t, estimators=estimator, units="rad/s", gaps="split", level=0.95)
        assert "pooled over 2 segments" in split["note"]
        assert split["n_samples"] == len(cut)
        assert "gaps split: 1 gaps; analysed as 2 segments" in split["preprocessing"][0]
        # The gap-free record reaches one octave further (its longest term spans the gap). At
        # the split's last tau (half a segment: EDF ~ 2) the two are nearly independent
        # estimates: there their intervals must overlap; everywhere else each estimate lies in
        # the other's 95 % interval.
        whole_at = {q["m"]: q for q in whole["points"]}
        assert len(split["points"]) >= len(whole["points"]) - 1
        for k, p in enumerate(split["points"]):
            q = whole_at[p["m"]]
            assert p["n"] < q["n"]
            if k == len(split["points"]) - 1:
                assert p["ci_low"] <= q["ci_high"] and q["ci_low"] <= p["ci_high"], (estimator, p["m"])
                continue
            assert q["ci_low"] <= p["dev"] <= q["ci_high"], (estimator, p["m"])
            assert p["ci_low"] <= q["dev"] <= p["ci_high"], (estimator, p["m"])
    with pytest.raises(ValueError, match="totdev cannot be pooled"):
        imunoise.dev(cut, time=t, estimators="totdev", gaps="split")
    with pytest.raises(ValueError, match="needs the timestamps"):
        imunoise.dev(cut, 100.0, gaps="split")
    with pytest.raises(ValueError, match="needs the timestamps"):
        imunoise.fit(cut, 100.0, gaps="split")


def test_fit_of_a_split_record_holds_the_true_n(gappy):
    _, cut, t = gappy
    r = imunoise.fit(cut, time=t, units="rad/s", gaps="split", level=0.99)
    n = r["terms"]["N"]
    n_true = 1e-3 / math.sqrt(100.0)
    assert n["ci_low"] <= n_true <= n["ci_high"]
    assert r["rate_hz"] == pytest.approx(100.0)
    assert any("pooled over 2 segments" in w for w in r["diagnostics"]["warnings"])
    assert r["preprocessing"][0].startswith("gaps split")


def test_keywords_give_the_command_lines_document(tmp_path):
    """The same samples through `imunoise dev --skip 20 --detrend linear --outliers report
    --davar --temperature` and through imunoise.dev(...): the same preprocessing lines and curve."""
    # The executable of the same build: <build>/apps/imunoise/imunoise, the package being
    # <build>/python/imunoise; IMUNOISE_CLI overrides.
    root = os.path.join(os.path.dirname(os.path.abspath(imunoise.__file__)), "..", "..")
    cli = os.environ.get("IMUNOISE_CLI") or next(
        (c for c in [os.path.join(root, "apps", "imunoise", "imunoise"), os.path.join(root, "imunoise")]
         if os.path.isfile(c)), None) or shutil.which("imunoise")
    if cli is None:
        pytest.skip("no imunoise executable in this build (set IMUNOISE_CLI)")
    rng = np.random.default_rng(9)
    n = 60_000
    t = np.arange(n) / 100.0
    temp = 20 + 10 * np.arange(n) / n
    gx = rng.standard_normal(n) * 0.01 + 0.05 * np.exp(-t / 30) + 2e-6 * t
    path = tmp_path / "r.csv"
    with open(path, "w") as f:
        f.write("t,gx,temp\n")
        for i in range(n):
            f.write(f"{t[i]:.2f},{gx[i]!r},{temp[i]!r}\n")
    args = ["--skip", "20", "--detrend", "linear", "--outliers", "report", "--davar", "--temperature", "temp"]
    out = subprocess.run([cli, "dev", str(path), "--time-column", "t", "--column", "gx", "--units", "rad/s",
                          "--format", "json", *args], capture_output=True, text=True, check=True).stdout
    from_cli = json.loads(out)
    mine = imunoise.dev(gx, time=t, units="rad/s", skip=20, detrend="linear", outliers="report", davar=True,
                        temperature=temp)
    assert mine["preprocessing"] == from_cli["preprocessing"]
    assert mine["n_samples"] == from_cli["n_samples"] == n - 2000
    assert mine["davar"]["stationary"] == from_cli["davar"]["stationary"]
    for p, q in zip(mine["points"], from_cli["points"]):
        assert p["dev"] == pytest.approx(q["dev"], rel=1e-9)
    assert len(mine["temperature_bins"]) == len(from_cli["temperature_bins"]) == 2
    assert mine["temperature_bins"][0]["fit"]["terms"]["N"]["value"] == pytest.approx(
        from_cli["temperature_bins"][0]["fit"]["terms"]["N"]["value"], rel=1e-9)


def test_temperature_fit_per_bin_and_bad_keywords():
    rng = np.random.default_rng(4)
    n = 200_000
    temp = np.where(np.arange(n) < n // 2, 10.0, 30.0)
    sd = np.where(temp > 20, 3e-3, 1e-3)
    x = rng.standard_normal(n) * sd
    r = imunoise.fit(x, 100.0, units="rad/s", temperature=temp, temperature_bin=10.0, level=0.99)
    bins = r["temperature_bins"]
    assert [b["low"] for b in bins] == [10.0, 30.0]
    for b, s in zip(bins, [1e-3, 3e-3]):
        n_fit = b["fit"]["terms"]["N"]
        assert n_fit["ci_low"] <= s / 10.0 <= n_fit["ci_high"]
        assert b["fit"]["level"] == 0.99
    with pytest.raises(ValueError, match="one per sample"):
        imunoise.fit(x, 100.0, temperature=temp[:10])
    with pytest.raises(ValueError, match="detrend"):
        imunoise.dev(x, 100.0, detrend="cubic")
    with pytest.raises(ValueError, match="gaps="):
        imunoise.dev(x, 100.0, gaps="interpolate")
    with pytest.raises(ValueError, match="skip"):
        imunoise.dev(x, 100.0, skip="soon")


def test_mcap_written_by_the_reference_writer_reads_back_bit_for_bit(tmp_path):
    """The reference TypeScript writer (@mcap/core, tests/io/mcap_writer; `npm ci` there, as
    .ci/run does), zstd chunks with a summary, read back against the values it saved."""
    writer = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "io", "mcap_writer")
    node = shutil.which("node")
    if node is None or not os.path.isdir(os.path.join(writer, "node_modules")):
        pytest.skip("node or tests/io/mcap_writer/node_modules missing (run npm ci there)")
    path = str(tmp_path / "imu.mcap")
    subprocess.run([node, os.path.join(writer, "write_mcap.js"), path, "zstd", "1500", "200", "summary"], check=True)
    expected = np.fromfile(path + ".expected", dtype="<f8").reshape(-1, 7)
    rec = imunoise.read(path, topic="/imu")
    assert rec.format == "MCAP" and rec.stream == "/imu"
    assert rec.message_type == "sensor_msgs/msg/Imu"
    assert len(rec) == 1500
    np.testing.assert_array_equal(rec.to_array(), expected[:, 1:])
    np.testing.assert_allclose(rec.time_s, expected[:, 0] * 1e-9, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="/imu"):
        imunoise.read(path, topic="/nope")


WRITERS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "io", "writers")


def test_ros2_db3_bag_and_px4_ulog_read_like_the_other_containers(tmp_path):
    """The ROS 2 SQLite bag and the PX4 log of the io tests' writers (tests/io/writers)."""
    bag = str(tmp_path / "bag")
    subprocess.run(["/usr/bin/python3", os.path.join(WRITERS, "write_db3.py"), bag, "1200"], check=True)
    expected = np.fromfile(os.path.join(bag, "expected.f64"), dtype="<f8").reshape(-1, 7)
    rec = imunoise.read(bag, topic="/imu")
    assert rec.format == "ROS 2 bag (SQLite)" and rec.message_type == "sensor_msgs/msg/Imu"
    np.testing.assert_array_equal(rec.to_array(), expected[:, 1:])  # bit for bit
    np.testing.assert_array_equal(np.round(rec.time_s * 1e9), expected[:, 0])
    assert rec.rate == pytest.approx(200.0)
    with pytest.raises(ValueError, match="/temperature"):
        imunoise.read(bag, topic="/imu/data")

    log = str(tmp_path / "log.ulg")
    subprocess.run(["/usr/bin/python3", os.path.join(WRITERS, "write_ulog.py"), log, "1000"], check=True)
    combined = imunoise.read(log, topic="sensor_combined")
    assert combined.format == "PX4 ULog" and len(combined) == 1000 and combined.rate == pytest.approx(200.0)
    assert any("dropped data 2 times (45 ms in all)" in note for note in combined.notes)
    one = imunoise.read(log, topic="sensor_gyro", column=["gyro1_x", "gyro1_y", "gyro1_z"])
    assert one.channel_names == ["gyro1_x", "gyro1_y", "gyro1_z"] and one.to_array().shape == (1000, 3)
    assert one.time_s[0] == pytest.approx(1.234e-3)  # instance 1 is sampled 1234 µs after instance 0
    with pytest.raises(ValueError, match="sampled at different times"):
        imunoise.read(log, topic="sensor_gyro")
    with pytest.raises(ValueError, match="no topic sensor_mag"):
        imunoise.read(log, topic="sensor_mag")
