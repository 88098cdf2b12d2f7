"""A PEP 517 build backend for the Lucent Python package that needs no package index (so that
`pip install ./python` works offline): it zips lucent/*.py into a wheel, with the repository's
build/liblucent.so when there is one (or $LUCENT_BUILD_DIR's), so that the installed package
loads the library it was built with. Without it the package looks for an installed Lucent."""
import base64
import glob
import hashlib
import io
import os
import sysconfig
import tarfile
import zipfile

NAME, VERSION = "lucent", "0.1.0"
HERE = os.path.dirname(os.path.abspath(__file__))
METADATA = ("Metadata-Version: 2.1\nName: %s\nVersion: %s\nSummary: Lucent: rendering translucent materials "
            "(ctypes bindings over liblucent.so)\nRequires-Python: >=3.8\n" % (NAME, VERSION))


def _library():
    build = os.environ.get("LUCENT_BUILD_DIR", os.path.join(HERE, "..", "build"))
    libs = sorted(glob.glob(os.path.join(build, "liblucent.so.*.*.*")))
    return libs[-1] if libs else None


def _files():
    out = [(os.path.join("lucent", os.path.basename(p)), p) for p in sorted(glob.glob(os.path.join(HERE, "lucent", "*.py")))]
    lib = _library()
    if lib:
        out.append((os.path.join("lucent", "liblucent.so"), lib))
    return out, lib is not None


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    files, native = _files()
    tag = "py3-none-" + (sysconfig.get_platform().replace("-", "_").replace(".", "_") if native else "any")
    dist = "%s-%s.dist-info" % (NAME, VERSION)
    path = os.path.join(wheel_directory, "%s-%s-%s.whl" % (NAME, VERSION, tag))
    records = []
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        def add(name, data):
            z.writestr(name, data)
            records.append(_record_line(name, data))
        for name, src in files:
            with open(src, "rb") as f:
                add(name, f.read())
        add(dist + "/METADATA", METADATA.encode())
        add(dist + "/WHEEL", ("Wheel-Version: 1.0\nGenerator: lucent_build\nRoot-Is-Purelib: %s\nTag: %s\n"
                              % ("false" if native else "true", tag)).encode())
        add(dist + "/top_level.txt", b"lucent\n")
        records.append(dist + "/RECORD,,")
        z.writestr(dist + "/RECORD", "\n".join(records) + "\n")
    return os.path.basename(path)


def build_sdist(sdist_directory, config_settings=None):
    base = "%s-%s" % (NAME, VERSION)
    path = os.path.join(sdist_directory, base + ".tar.gz")
    with tarfile.open(path, "w:gz") as t:
        for name in ["pyproject.toml", "lucent_build.py"] + [os.path.join("lucent", os.path.basename(p))
                                                             for p in glob.glob(os.path.join(HERE, "lucent", "*.py"))]:
            t.add(os.path.join(HERE, name), arcname=os.path.join(base, name))
        info = tarfile.TarInfo(os.path.join(base, "PKG-INFO"))
        data = METADATA.encode()
        info.size = len(data)
        t.addfile(info, io.BytesIO(data))
    return os.path.basename(path)
